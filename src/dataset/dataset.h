#pragma once
// A posed-photo dataset, as NeRF-style training reads it: frames (image + intrinsics +
// camera-to-world pose), a train/test split, and estimates of the scene box and near/far.
//
//   DatasetOptions o;  o.downscale = 4;
//   Dataset d = loadDataset("/data/lego", o);         // folder, transforms*.json or *_par.txt folder
//   glm::dvec3 org, dir;  frameRay(d.frames[0], 100.5, 20.5, org, dir);
//
// Conventions, for every format:
// - Poses are camera-to-world 4x4 in OpenGL/NeRF camera axes: the camera looks down -z,
//   +y is up in the image, +x right. World units are the dataset's own.
// - Images are float RGB in [0, 1] holding the *encoded* values stored in the file (sRGB for
//   PNG/JPEG; EXR values as stored), not linearised: NeRF-style training fits those values.
//   Images with alpha are composited onto `DatasetOptions::background`, in premultiplied form
//   (c*a + bg*(1-a)), as Blender-synthetic training does.
// - Pixel centres are at half-integers (intrinsics.h).
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "dataset/intrinsics.h"

namespace inim {

struct Box3d {
  glm::dvec3 lo{0.0}, hi{0.0};
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  glm::dvec3 extent() const { return hi - lo; }
  bool contains(const glm::dvec3& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
};

struct DatasetFrame {
  std::string imagePath;     // resolved file that was read
  int sourceIndex = 0;       // index of the frame in the dataset file
  Intrinsics intrinsics;     // of the image as loaded (after downscaling)
  glm::dmat4 cameraToWorld{1.0};  // OpenGL axes (camera looks down -z)
  Image image;               // channels R,G,B; empty when DatasetOptions::loadImages is false
  bool hadAlpha = false;     // the file had alpha, composited onto the background

  glm::dvec3 position() const { return glm::dvec3(cameraToWorld[3]); }
  glm::dvec3 forward() const { return -glm::normalize(glm::dvec3(cameraToWorld[2])); }
};

struct DatasetOptions {
  int downscale = 1;           // integer factor >= 1: images and intrinsics shrink by it
  int holdoutEvery = 8;        // frame i is a test frame when i % holdoutEvery == 0; 0 = none
  glm::vec3 background{1.0f};  // what transparent pixels become (Blender default: white)
  bool loadImages = true;      // false: read only image headers (sizes), no pixels
  // Overrides of the estimates below.
  std::optional<Box3d> sceneBox;
  std::optional<double> nearPlane, farPlane;
};

struct Dataset {
  std::string file;      // the transforms*.json or *_par.txt read
  std::string format;    // "blender", "nerfstudio", "instant-ngp" or "middlebury"
  std::vector<DatasetFrame> frames;   // only frames whose image exists, in file order
  std::vector<int> train, test;  // indices into frames
  int skippedFrames = 0;       // listed frames without an image file
  glm::vec3 background{1.0f};  // the compositing background used for images with alpha
  // Scene box and near/far along camera rays (scene_box.h), or the overrides.
  Box3d sceneBox;
  double nearPlane = 0, farPlane = 0;
  // instant-ngp only: the box its "aabb_scale" / "scale" / "offset" describe, in the dataset's
  // world units (instant-ngp maps world p to ngp space by p * scale + offset, then a y,z,x axis cycle,
  // and marches rays inside [0.5 - aabb_scale/2, 0.5 + aabb_scale/2]^3 there). Informational:
  // poses are NOT rescaled by it, and the scene box estimate does not use it; pass it as
  // DatasetOptions::sceneBox to adopt it.
  std::optional<Box3d> ngpBox;
};

// Loads `path`: a transforms*.json (Blender, Nerfstudio, instant-ngp), a Middlebury *_par.txt,
// or a folder holding transforms.json, transforms_train.json, or one *_par.txt.
// Throws InputError (file, key, value, expected) for bad input; warns once on stderr about
// frames whose image is missing, and skips them.
Dataset loadDataset(const std::string& path, const DatasetOptions& options = {});

// The ray through continuous pixel position (px, py) (pixel centres at i + 0.5), in world
// coordinates, with lens distortion removed. `dir` is unit length.
void frameRay(const DatasetFrame& frame, double px, double py, glm::dvec3& origin, glm::dvec3& dir);
// Projects a world point into the frame's pixels (with distortion). False when the point is
// not in front of the camera.
bool projectToFrame(const DatasetFrame& frame, const glm::dvec3& world, glm::dvec2& pixel);

// The split rule: index i is a test index when holdoutEvery > 0 and i % holdoutEvery == 0.
void splitTrainTest(int count, int holdoutEvery, std::vector<int>& train, std::vector<int>& test);

}  // namespace inim
