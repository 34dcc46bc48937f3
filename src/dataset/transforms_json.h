#pragma once
// transforms.json in its three dialects, read into a DatasetManifest:
// - Blender synthetic (NeRF): "camera_angle_x" [+ "camera_angle_y"], frames with
//   "file_path" (often without extension, "./train/r_0") and "transform_matrix".
// - Nerfstudio: "fl_x fl_y cx cy w h", distortion "k1 k2 p1 p2", "camera_model" (OPENCV or
//   PINHOLE; fisheye and equirectangular models are rejected); any of these per frame too,
//   where they override the global values.
// - instant-ngp: as Nerfstudio, plus optional "aabb_scale", "scale", "offset" (see
//   Dataset::ngpBox for what is done with them: recorded, never applied to the poses).
// Keys that would change the camera model and cannot be honoured (k3, k4 non-zero,
// is_fisheye) are errors. The extras those tools write that do not bear on poses or images
// (instant-ngp's "sharpness", Nerfstudio's "colmap_im_id", "mask_path", "depth_file_path",
// "applied_transform", "ply_file_path", the Blender set's "rotation", fovx/fovy) are ignored;
// any other key is an error naming it, so a misspelling (fl_z) is not silently dropped.
// Whole-number keys (w, h) may be written as floats with no fraction part (1080.0).
#include <string>

#include "dataset/manifest.h"

namespace inim {

DatasetManifest readTransformsJson(const std::string& path);

}  // namespace inim
