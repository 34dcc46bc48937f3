#pragma once
// Colour maps for heat maps: a value in [0, 1] to a display colour (sRGB-encoded, in [0, 1]).
#include "core/geometry.h"

namespace inim {

enum class ColorMap {
  Viridis,  // dark blue - green - yellow, lightness rising (matplotlib's default map)
  Grey,     // black to white
};

// The colour of t on a map (t clamped to [0, 1]; NaN gives t = 0). Lightness rises with t.
Vec3 colorMap(ColorMap map, double t);

}  // namespace inim
