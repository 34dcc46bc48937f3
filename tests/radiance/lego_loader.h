#pragma once
// Test/benchmark-only loader of the Blender "Lego" NeRF scene (transforms_train.json with
// camera_angle_x and OpenGL camera-to-world matrices, RGBA PNGs). Downscales by box
// averaging of premultiplied colour, composites onto white and turns pixels into rays.
// The real dataset loader lives in src/dataset; this one exists so the radiance stage can
// be benchmarked on its own.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "radiance/trainer.h"

namespace lego {

struct View {
  int width = 0, height = 0;
  std::vector<inim::Vec3> rgb;      // sRGB-encoded, composited on white, row 0 at the top
  std::vector<inim::Point3> origin;  // one ray per pixel
  std::vector<inim::Vec3> dir;
};

inline View loadView(const std::string& png, const float c2w[4][4], float cameraAngleX, int factor) {
  auto in = OIIO::ImageInput::open(png);
  if (!in) throw std::runtime_error("cannot open " + png);
  const OIIO::ImageSpec& spec = in->spec();
  int w = spec.width, h = spec.height, nc = spec.nchannels;
  std::vector<float> px(size_t(w) * h * nc);
  in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data());
  in->close();
  View v;
  v.width = w / factor;
  v.height = h / factor;
  float focal = 0.5f * float(v.width) / std::tan(0.5f * cameraAngleX);
  for (int j = 0; j < v.height; ++j)
    for (int i = 0; i < v.width; ++i) {
      inim::Vec3 sum(0.0f);
      float a = 0.0f;
      for (int y = 0; y < factor; ++y)
        for (int x = 0; x < factor; ++x) {
          const float* p = &px[(size_t(j * factor + y) * w + (i * factor + x)) * nc];
          float alpha = nc > 3 ? p[3] : 1.0f;
          sum += alpha * inim::Vec3(p[0], p[1], p[2]);
          a += alpha;
        }
      float inv = 1.0f / float(factor * factor);
      v.rgb.push_back(sum * inv + inim::Vec3(1.0f - a * inv));
      inim::Vec3 d((float(i) + 0.5f - 0.5f * v.width) / focal,
                   -(float(j) + 0.5f - 0.5f * v.height) / focal, -1.0f);
      inim::Vec3 world(c2w[0][0] * d.x + c2w[0][1] * d.y + c2w[0][2] * d.z,
                       c2w[1][0] * d.x + c2w[1][1] * d.y + c2w[1][2] * d.z,
                       c2w[2][0] * d.x + c2w[2][1] * d.y + c2w[2][2] * d.z);
      v.dir.push_back(world);
      v.origin.push_back(inim::Point3(c2w[0][3], c2w[1][3], c2w[2][3]));
    }
  return v;
}

// All frames of transforms_train.json under `dir`, downscaled by `factor`.
inline std::vector<View> loadScene(const std::string& dir, int factor) {
  std::ifstream f(dir + "/transforms_train.json");
  if (!f) throw std::runtime_error("cannot open " + dir + "/transforms_train.json");
  nlohmann::json j = nlohmann::json::parse(f);
  float angle = j.at("camera_angle_x").get<float>();
  std::vector<View> views;
  for (const auto& frame : j.at("frames")) {
    float m[4][4];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m[r][c] = frame.at("transform_matrix")[r][c].get<float>();
    std::string path = frame.at("file_path").get<std::string>();
    if (path.rfind("./", 0) == 0) path = path.substr(2);
    views.push_back(loadView(dir + "/" + path + ".png", m, angle, factor));
  }
  return views;
}

inline void appendRays(const View& v, inim::TrainingRays& rays) {
  rays.origin.insert(rays.origin.end(), v.origin.begin(), v.origin.end());
  rays.dir.insert(rays.dir.end(), v.dir.begin(), v.dir.end());
  rays.rgb.insert(rays.rgb.end(), v.rgb.begin(), v.rgb.end());
}

}  // namespace lego
