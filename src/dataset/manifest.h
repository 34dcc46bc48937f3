#pragma once
// What a dataset file says before any image is opened: per frame, the image path as written,
// the pose and what is known of the intrinsics. Format parsers (transforms_json.h,
// middlebury.h) produce it; loadDataset (dataset.h) resolves images and fills the rest.
#include <optional>
#include <string>
#include <vector>

#include "dataset/dataset.h"

namespace inim {

struct FrameSpec {
  std::string filePath;           // as written, relative to the dataset file's folder
  std::string key;                // key path for messages, e.g. "frames[3].file_path"
  glm::dmat4 cameraToWorld{1.0};  // OpenGL axes
  // Intrinsics at the file's resolution. width/height 0 = take them from the image; fx 0 =
  // derive from angleX (and fy from angleY, else fx) once the width is known; cx/cy NaN =
  // the image centre (a given negative cx is a value, checked against the image).
  Intrinsics intrinsics;
  double angleX = 0, angleY = 0;  // radians (Blender's camera_angle_x/_y)
};

struct DatasetManifest {
  std::string file;
  std::string format;
  std::vector<FrameSpec> frames;
  std::optional<Box3d> ngpBox;
};

}  // namespace inim
