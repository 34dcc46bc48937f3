#include "synthesis/panel_color.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace inim {

const char* gamutName(GamutMapping g) { return g == GamutMapping::Clip ? "clip" : "desaturate"; }

GamutMapping parseGamut(const std::string& s, const std::string& key) {
  if (s == "clip") return GamutMapping::Clip;
  if (s == "desaturate") return GamutMapping::Desaturate;
  throw InputError("", key, "\"" + s + "\"", "clip or desaturate");
}

PanelColor::PanelColor(const Panel& panel) : peak_(panel.peakLuminanceCdM2) {
  glm::dmat3 m(0.0);
  for (int c = 0; c < kNumPrimaries; ++c) m[c] = spectrumToXYZ(*primarySpectrum(panel.primaries[size_t(c)]));
  double Yw = m[0].y + m[1].y + m[2].y;
  const std::string file = panel.file.empty() ? "panel" : panel.file;
  if (!(Yw > 0.0) || !std::isfinite(Yw))
    throw InputError(file, "primaries", "zero luminance", "primaries that emit visible light");
  m /= Yw;
  double det = glm::determinant(m);
  if (!(std::abs(det) > 1e-9))
    throw InputError(file, "primaries", "linearly dependent XYZ (determinant " + std::to_string(det) + ")",
                     "three primaries of distinct chromaticity");
  driveToXYZ_ = m;
  xyzToDrive_ = glm::inverse(m);
}

Vec2 PanelColor::primaryXY(int c) const {
  Vec3d v = driveToXYZ_[c];
  double s = v.x + v.y + v.z;
  return {float(v.x / s), float(v.y / s)};
}

Vec2 PanelColor::whiteXY() const {
  Vec3d v = whiteXYZ();
  double s = v.x + v.y + v.z;
  return {float(v.x / s), float(v.y / s)};
}

Vec3d PanelColor::driveFromSpectrum(const Spectrum& s) const { return driveFromXYZ(spectrumToXYZ(s)); }

Vec3d PanelColor::d65WhiteGains() const {
  Vec3d d = driveFromXYZ(d65WhiteXyz());
  return {1.0 / d.x, 1.0 / d.y, 1.0 / d.z};
}

void rgbToXYZInPlace(std::span<Vec3> rgb, const std::string& colorSpace) {
  if (rgb.empty()) return;
  Image img(int(rgb.size()), 1, {"R", "G", "B"});
  for (size_t i = 0; i < rgb.size(); ++i)
    for (int c = 0; c < 3; ++c) img.data[i * 3 + size_t(c)] = rgb[i][c];
  ColorSystem::instance().convertImage(img, colorSpace, "cie_xyz_d65");
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = Vec3(img.data[i * 3], img.data[i * 3 + 1], img.data[i * 3 + 2]);
}

GamutStats& GamutStats::operator+=(const GamutStats& o) {
  pixels += o.pixels;
  outOfGamut += o.outOfGamut;
  negative += o.negative;
  overRange += o.overRange;
  maxChannel = std::max(maxChannel, o.maxChannel);
  minChannel = std::min(minChannel, o.minChannel);
  return *this;
}

bool mapToGamut(Vec3& d, const Vec3& w, GamutMapping mapping) {
  float lo = std::min(d.x, std::min(d.y, d.z)), hi = maxComponent(d);
  bool out = lo < -kGamutTolerance || hi > 1.0f + kGamutTolerance;
  if (!(lo >= 0.0f && hi <= 1.0f)) {  // also catches NaN
    if (!isFinite(d)) {
      d = Vec3(0.0f);
      return true;
    }
    if (mapping == GamutMapping::Desaturate && out) {
      float Y = glm::dot(w, d);
      if (Y <= 0.0f) {
        d = Vec3(0.0f);
      } else if (Y >= 1.0f) {
        d = Vec3(1.0f);
      } else {
        // Largest t in [0, 1] with Y + t (d - Y) inside [0, 1] on every channel.
        float t = 1.0f;
        for (int c = 0; c < 3; ++c) {
          if (d[c] > 1.0f) t = std::min(t, (1.0f - Y) / (d[c] - Y));
          if (d[c] < 0.0f) t = std::min(t, Y / (Y - d[c]));
        }
        d = Vec3(Y) + t * (d - Vec3(Y));
      }
    }
    d = glm::clamp(d, Vec3(0.0f), Vec3(1.0f));  // clip, and rounding of the desaturated result
  }
  return out;
}

FieldToDrive::FieldToDrive(const PanelColor& color, const DriveSettings& settings)
    : settings_(settings),
      xyzToDrive_(glm::mat3(color.xyzToDrive())),
      gains_(Vec3(float(settings.exposure))),
      lumWeights_(Vec3(color.luminanceWeights())) {
  if (settings.whiteBalanceD65) gains_ *= Vec3(color.d65WhiteGains());
}

Vec3 FieldToDrive::fromNative(const Vec3& nativeDrive, GamutStats& stats) const {
  Vec3 d = nativeDrive * gains_;
  mapToGamut(d, lumWeights_, settings_.gamut, stats);
  if (!settings_.correction) return d;
  const Vec3d c = settings_.correction->apply(Vec3d(d));
  return glm::clamp(Vec3(c), Vec3(0.0f), Vec3(1.0f));
}

Vec3 FieldToDrive::fromXyz(const Vec3& xyz) const {
  GamutStats unused;
  return fromXyz(xyz, unused);
}

}  // namespace inim
