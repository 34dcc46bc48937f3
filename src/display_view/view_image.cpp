#include "display_view/view_image.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "spectral/color.h"

namespace inim {

Exposure parseExposure(const std::string& text, const std::string& key) {
  Exposure e;
  if (text == "auto") return e;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end || !(v > 0.0) || !std::isfinite(v))
    throw InputError("", key, "\"" + text + "\"", "a number > 0 or auto");
  e.automatic = false;
  e.factor = v;
  return e;
}

double exposureFactor(const Image& img, const CameraSensor& sensor, const Exposure& e) {
  if (!e.automatic) return e.factor;
  const glm::dmat3 toRec709 = glm::dmat3(ColorSystem::xyzToRec709()) * sensor.colorFit().cameraToXyz;
  const int b = std::max(1, int(std::lround(img.width / 200.0)));
  std::vector<float> v;
  v.reserve(size_t(img.width / b + 1) * size_t(img.height / b + 1));
  for (int by = 0; by < img.height; by += b)
    for (int bx = 0; bx < img.width; bx += b) {
      Vec3d c(0.0);
      int n = 0;
      for (int y = by; y < std::min(img.height, by + b); ++y)
        for (int x = bx; x < std::min(img.width, bx + b); ++x, ++n)
          c += Vec3d(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
      c /= double(std::max(1, n));
      if (!(c.x > 0.0 || c.y > 0.0 || c.z > 0.0)) continue;
      const Vec3d r = toRec709 * c;
      const double m = std::max(r.x, std::max(r.y, r.z));
      if (m > 0.0 && std::isfinite(m)) v.push_back(float(m));
    }
  if (v.empty()) return 1.0;
  const double q = std::clamp(e.percentile, 0.0, 100.0) / 100.0;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k] > 0.0f ? e.target / double(v[k]) : 1.0;
}

Image scaledImage(const Image& img, double k) {
  Image out = img;
  const int nc = img.numChannels();
  for (size_t i = 0; i < out.data.size(); ++i)
    if (int(i % size_t(nc)) < 3) out.data[i] = float(double(out.data[i]) * k);
  return out;
}

Image cameraRgbToSrgb(const Image& img, const CameraSensor& sensor) {
  Image out(img.width, img.height, {"R", "G", "B"});
  const glm::dmat3 M = sensor.colorFit().cameraToXyz;
  parallelForRange(int64_t(img.width) * img.height, [&](int64_t a, int64_t b) {
    for (int64_t i = a; i < b; ++i) {
      const int x = int(i % img.width), y = int(i / img.width);
      const Vec3d xyz = M * Vec3d(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(xyz[c]);
    }
  });
  ColorSystem::instance().convertImage(out, "cie_xyz_d65", "srgb");
  for (auto& v : out.data) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  return out;
}

}  // namespace inim
