#include "splats/splat_placement.h"

#include <algorithm>
#include <cmath>

namespace inim {

SplatBox robustSplatBox(const Gaussians& g, float lowPct, float highPct) {
  SplatBox box{Vec3(0.0f), Vec3(0.0f)};
  const size_t n = g.size();
  if (n == 0) return box;
  std::vector<float> v(n);
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < n; ++i) v[i] = g.position[i][a];
    const auto pick = [&](float pct) {
      const size_t k = std::min(n - 1, size_t(std::lround(pct / 100.0f * float(n - 1))));
      std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
      return v[k];
    };
    box.lo[a] = pick(lowPct);
    box.hi[a] = pick(highPct);
  }
  return box;
}

SplatFrame defaultSplatFrame(const Gaussians& g, float widthMm, float heightMm, float fill) {
  SplatFrame f;
  f.rotation = glm::mat3(Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1));  // 180 deg about x
  const SplatBox box = robustSplatBox(g);
  const Vec3 extent = box.hi - box.lo;
  const float sx = extent.x > 0.0f ? fill * widthMm / extent.x : kInfinity;
  const float sy = extent.y > 0.0f ? fill * heightMm / extent.y : kInfinity;
  f.scale = std::min(sx, sy);
  if (!std::isfinite(f.scale)) f.scale = 1.0f;  // a single splat or a flat row: keep its units as mm
  f.translate = -f.scale * (f.rotation * (0.5f * (box.lo + box.hi)));
  return f;
}

}  // namespace inim
