#include "analysis/colormap.h"

#include <algorithm>
#include <cmath>

namespace inim {

namespace {

// Viridis (van der Walt and Smith, CC0) sampled at every 16th of its 256 entries and at the
// last, interpolated linearly between them.
constexpr float kViridis[17][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.282327f, 0.094955f, 0.417331f}, {0.278826f, 0.175490f, 0.483397f},
    {0.258965f, 0.251537f, 0.524736f}, {0.229739f, 0.322361f, 0.545706f}, {0.199430f, 0.387607f, 0.554642f},
    {0.172719f, 0.448791f, 0.557885f}, {0.149039f, 0.508051f, 0.557250f}, {0.127568f, 0.566949f, 0.550556f},
    {0.120638f, 0.625828f, 0.533488f}, {0.157851f, 0.683765f, 0.501686f}, {0.246070f, 0.738910f, 0.452024f},
    {0.369214f, 0.788888f, 0.382914f}, {0.515992f, 0.831158f, 0.294279f}, {0.678489f, 0.863742f, 0.189503f},
    {0.845561f, 0.887322f, 0.099702f}, {0.993248f, 0.906157f, 0.143936f}};
// Entry of each sample in the 256-entry map.
constexpr double kViridisAt[17] = {0, 16, 32, 48, 64, 80, 96, 112, 128, 144, 160, 176, 192, 208, 224, 240, 255};

Vec3 viridis(double t) {
  const double e = t * 255.0;
  int k = 0;
  while (k < 15 && e > kViridisAt[k + 1]) ++k;
  const double f = std::clamp((e - kViridisAt[k]) / (kViridisAt[k + 1] - kViridisAt[k]), 0.0, 1.0);
  Vec3 c;
  for (int i = 0; i < 3; ++i) c[i] = float((1.0 - f) * kViridis[k][i] + f * kViridis[k + 1][i]);
  return c;
}

}  // namespace

Vec3 colorMap(ColorMap map, double t) {
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  switch (map) {
    case ColorMap::Grey: return Vec3(float(t));
    case ColorMap::Viridis: break;
  }
  return viridis(t);
}

}  // namespace inim
