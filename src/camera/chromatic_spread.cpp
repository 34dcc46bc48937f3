#include "camera/chromatic_spread.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace inim {

namespace {

// Where the ray through aperture point `a` at `lambdaNm` crosses the plane; none when blocked
// or parallel to it.
std::optional<Vec3d> crossing(const CameraModel& camera, Vec2 pixel, const Vec2d& a, float lambdaNm) {
  Ray r;
  if (!(camera.apertureRay(pixel, a, lambdaNm, r) > 0.0f)) return std::nullopt;
  const Vec3d n = camera.back();
  const double dn = glm::dot(Vec3d(r.d), n);
  if (!(std::abs(dn) > 1e-12)) return std::nullopt;
  const double t = glm::dot(camera.pose().lookAt - Point3d(r.o), n) / dn;
  return Point3d(r.o) + t * Vec3d(r.d);
}

// The largest 450/650 nm offset at one sensor point, over its pixel footprint; 0 when no aperture
// point passes at all three wavelengths.
double spreadAt(const CameraModel& camera, Vec2 pixel) {
  Vec2d lo, hi;
  if (!camera.apertureDomain(pixel, lo, hi)) return 0.0;
  const Vec2d mid = 0.5 * (lo + hi);
  const auto c0 = crossing(camera, pixel, mid, 550.0f), c1 = crossing(camera, pixel + Vec2(1.0f, 0.0f), mid, 550.0f);
  if (!c0 || !c1) return 0.0;
  const double footprint = glm::length(*c1 - *c0);
  if (!(footprint > 0.0)) return 0.0;
  double worst = 0.0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const Vec2d a(lo.x + (i + 0.5) / 3.0 * (hi.x - lo.x), lo.y + (j + 0.5) / 3.0 * (hi.y - lo.y));
      const auto g = crossing(camera, pixel, a, 550.0f);
      const auto b = crossing(camera, pixel, a, 450.0f), r = crossing(camera, pixel, a, 650.0f);
      if (!g || !b || !r) continue;
      worst = std::max({worst, glm::length(*b - *g), glm::length(*r - *g)});
    }
  return worst / footprint;
}

}  // namespace

double chromaticSpreadPx(const CameraModel& camera) {
  if (!camera.isDispersive()) return 0.0;
  const float w = float(camera.width()), h = float(camera.height());
  double worst = 0.0;
  for (const Vec2 p : {Vec2(0.5f * w, 0.5f * h), Vec2(0.05f * w, 0.05f * h), Vec2(0.95f * w, 0.05f * h),
                       Vec2(0.05f * w, 0.95f * h), Vec2(0.95f * w, 0.95f * h)})
    worst = std::max(worst, spreadAt(camera, p));
  return worst;
}

}  // namespace inim
