#include "colour_chain/colour_chain.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "spectral/color.h"

namespace inim {

Vec3d PanelInput::quantise(const Vec3d& linearDrive) const {
  Vec3d d = glm::clamp(linearDrive, Vec3d(0.0), Vec3d(1.0));
  if (bits <= 0) return d;
  const double levels = std::ldexp(1.0, bits) - 1.0;
  for (int c = 0; c < 3; ++c) d[c] = eotf.decode(std::round(eotf.encode(d[c]) * levels) / levels);
  return d;
}

Vec3d representableInField(const Vec3d& xyz, const std::string& space) {
  if (space == "spectral") return xyz;
  const ColorSystem& cs = ColorSystem::instance();
  Vec3 rgb;
  try {
    rgb = cs.convert(Vec3(xyz), "cie_xyz_d65", space);
  } catch (const std::exception&) {
    throw InputError("", "field_space", "\"" + space + "\"",
                     "spectral or a linear colour space of the OCIO config (lin_rec709, display_p3, acescg)");
  }
  return Vec3d(cs.convert(glm::max(rgb, Vec3(0.0f)), space, "cie_xyz_d65"));
}

double calibrationExposure(const PanelColor& panel) {
  const Vec3d d = panel.driveFromXYZ(d65WhiteXyz());
  return 1.0 / std::max({d.x, d.y, d.z});
}

double deltaE2000(const Vec3d& a, const Vec3d& b, const Vec3d& white) {
  return ciede2000(xyzToLab(a, white), xyzToLab(b, white));
}

DeltaESummary summarise(std::vector<double> e) {
  DeltaESummary s;
  s.count = int(e.size());
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  double sum = 0.0;
  for (double v : e) sum += v;
  s.mean = sum / double(e.size());
  // Linear interpolation between order statistics (the "type 7" percentile).
  const double k = 0.95 * double(e.size() - 1);
  const size_t i = size_t(std::floor(k));
  s.p95 = e[i] + (k - double(i)) * (e[std::min(i + 1, e.size() - 1)] - e[i]);
  s.max = e.back();
  return s;
}

PoseChain::PoseChain(const PoseResponse& response, const PanelInput& input)
    : response_(response), input_(input), xyzToDrive_(glm::inverse(response.xyzPerDrive)) {
  const Vec3d d = xyzToDrive_ * d65WhiteXyz();
  const double m = std::max({d.x, d.y, d.z});
  if (!(m > 0.0) || !std::isfinite(m))
    throw InputError("", "pose", response.pose.pose.describe(), "a pose from which the display's white can be measured");
  whiteY_ = 1.0 / m;
}

bool PoseChain::inGamut(const Vec3d& targetXyz, double tolerance) const {
  const Vec3d d = driveFor(targetXyz);
  return std::min({d.x, d.y, d.z}) >= -tolerance && std::max({d.x, d.y, d.z}) <= 1.0 + tolerance;
}

}  // namespace inim
