#pragma once
// transforms.json in its three dialects, read into a DatasetManifest:
// - Blender synthetic (NeRF): "camera_angle_x" [+ "camera_angle_y"], frames with
//   "file_path" (often without extension, "./train/r_0") and "transform_matrix".
// - Nerfstudio: "fl_x fl_y cx cy w h", distortion "k1 k2 p1 p2", "camera_model" (OPENCV or
//   PINHOLE; fisheye and equirectangular models are rejected); any of these per frame too,
//   where they override the global values.
// - instant-ngp: as Nerfstudio, plus optional "aabb_scale", "scale", "offset" (see
//   Dataset::ngpBox for what is done with them: recorded, never applied to the poses).
// Unknown keys are ignored (these files carry many tool-specific extras), but keys that would
// change the camera model and cannot be honoured (k3, k4 non-zero, is_fisheye) are errors.
#include <string>

#include "dataset/manifest.h"

namespace inim {

DatasetManifest readTransformsJson(const std::string& path);

}  // namespace inim
