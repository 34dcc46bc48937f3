#pragma once
// Helpers for the dataset and fitting tests: tiny images and dataset files written into the
// scratch folder (fixtures.h).
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "fixtures.h"

namespace dataset_test {

using fixtures::writeBytes;

// Writes an 8-bit PNG with `channels` (3 or 4) channels, every pixel `value` (straight alpha).
inline void writePng(const std::string& path, int w, int h, std::vector<float> value) {
  const int C = int(value.size());
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(w, h, C, OIIO::TypeDesc::UINT8);
  if (C == 4) {
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // values are straight: store them as given
  }
  std::vector<unsigned char> px(size_t(w) * h * C);
  for (size_t i = 0; i < px.size(); ++i) px[i] = (unsigned char)std::lround(value[i % C] * 255.0f);
  out->open(path, spec);
  out->write_image(OIIO::TypeDesc::UINT8, px.data());
  out->close();
}

// A camera-to-world matrix (OpenGL axes) at `eye` looking at `target`, up +y.
inline glm::dmat4 lookAtC2W(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up = {0, 1, 0}) {
  return glm::inverse(glm::lookAt(eye, target, up));  // glm::lookAt is world-to-camera (OpenGL)
}

inline nlohmann::json matrixJson(const glm::dmat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return rows;
}

// A fresh, empty dataset folder `name` inside the scratch folder.
inline std::string folder(const std::string& name) {
  const std::string d = fixtures::scratchPath(name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// n cameras on a ring of radius 4 at height 1, looking at the origin.
inline std::vector<glm::dmat4> ringPoses(int n) {
  std::vector<glm::dmat4> poses;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    poses.push_back(lookAtC2W({4 * std::cos(a), 1.0, 4 * std::sin(a)}, {0, 0, 0}));
  }
  return poses;
}

// A Blender-style dataset in folder `name`: camera_angle_x, paths without extension, n
// size x size images of one colour (RGB or straight RGBA) on ringPoses(n). Returns the folder.
inline std::string blenderDataset(const std::string& name, int n, int size, const std::vector<float>& rgba,
                                  const std::string& jsonName = "transforms_train.json") {
  const std::string d = folder(name);
  std::filesystem::create_directories(d + "/train");
  nlohmann::json j;
  j["camera_angle_x"] = 0.6911112070083618;
  const auto poses = ringPoses(n);
  for (int i = 0; i < n; ++i) {
    const std::string stem = "train/r_" + std::to_string(i);
    writePng(d + "/" + stem + ".png", size, size, rgba);
    j["frames"].push_back({{"file_path", "./" + stem}, {"rotation", 0.0125},
                           {"transform_matrix", matrixJson(poses[size_t(i)])}});
  }
  writeBytes(d + "/" + jsonName, j.dump(2));
  return d;
}

}  // namespace dataset_test
