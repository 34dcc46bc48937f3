#include "synthesis/eia_correction.h"

#include <algorithm>

#include "core/parallel.h"
#include "rays/ray_set.h"

namespace inim {

Image correctedEia(const EiLayout& L, const Image& eia, const ColourModel& correction) {
  const bool panelSized = eia.width == L.panelW && eia.height == L.panelH;
  const int x0 = panelSized ? L.panelCol0 : 0, y0 = panelSized ? L.panelRow0 : 0;
  const bool named = eia.channelIndex("R") >= 0 && eia.channelIndex("G") >= 0 && eia.channelIndex("B") >= 0;
  const int ch[3] = {named ? eia.channelIndex("R") : 0, named ? eia.channelIndex("G") : 1,
                     named ? eia.channelIndex("B") : 2};
  Image out = eia;
  parallelForRange(
      L.numRays(),
      [&](int64_t a, int64_t b) {
        for (int64_t r = a; r < b; ++r) {
          const PixelCoord p = eiaPixel(L, rayAddress(L, r));
          const int x = x0 + p.col, y = y0 + p.row;
          if (x < 0 || y < 0 || x >= eia.width || y >= eia.height) continue;
          const Vec3d d(eia.at(x, y, ch[0]), eia.at(x, y, ch[1]), eia.at(x, y, ch[2]));
          const Vec3d c = correction.apply(d);
          for (int k = 0; k < 3; ++k) out.at(x, y, ch[k]) = std::clamp(float(c[k]), 0.0f, 1.0f);
        }
      },
      nullptr, 1 << 14);
  return out;
}

}  // namespace inim
