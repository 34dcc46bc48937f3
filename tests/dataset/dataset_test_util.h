#pragma once
// Helpers for the dataset tests: tiny images and dataset files written into a scratch folder.
#include <OpenImageIO/imageio.h>

#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

namespace dataset_test {

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

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

}  // namespace dataset_test
