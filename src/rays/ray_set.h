#pragma once
// A set of display rays as float structure-of-arrays (24 bytes a ray), and the mapping
// between a ray's index, its EI and EI-local pixel, and its EIA / panel pixel.
//
// Ray order (the paper's, optics/README.md "Ray order"): EI column k from the left (outermost),
// then EI row from the BOTTOM, then EI-local column i from the left, then EI-local row from
// the BOTTOM (innermost). Inside one EI this is the ZPL macro's order (x outer, y inner, both
// increasing along +x / +y), and EIs follow the paper's microlensxperia9875.dat (x outer,
// y inner, increasing). RayAddress itself uses image conventions (rows from the top).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/ray_check.h"
#include "display/ei_layout.h"

namespace inim {

struct RaySet {
  std::vector<float> ox, oy, oz;  // origin, mm
  std::vector<float> dx, dy, dz;  // unit direction, toward the viewer for display rays

  size_t size() const { return ox.size(); }
  bool empty() const { return ox.empty(); }
  void resize(size_t n);
  Ray ray(size_t i) const { return {Point3(ox[i], oy[i], oz[i]), Vec3(dx[i], dy[i], dz[i])}; }
  void set(size_t i, const Vec3& o, const Vec3& d) {
    ox[i] = o.x, oy[i] = o.y, oz[i] = o.z;
    dx[i] = d.x, dy[i] = d.y, dz[i] = d.z;
  }
};

// Every ray of the set; `where` of ray i is "ray i" (0-based, as the set numbers them).
void checkRays(const RaySet& rays, const std::string& file);

// One ray's place: EI (k, l) with k columns from the left and l rows from the top, and the
// EI-local pixel (i, j), i columns from the EI's left, j rows from its top.
struct RayAddress {
  int k = 0, l = 0, i = 0, j = 0;
  bool operator==(const RayAddress&) const = default;
};
struct PixelCoord {
  int col = 0, row = 0;
  bool operator==(const PixelCoord&) const = default;
};

// Hex layouts (display/ei_layout.h): (i, j) is local to EI (k, l)'s eiW x eiH box, and only
// the pixels the EI owns are rays (rayIndex is -1 for the others); the ray order is the same
// with the pixels an EI does not own left out.
int64_t rayIndex(const EiLayout& L, const RayAddress& a);
RayAddress rayAddress(const EiLayout& L, int64_t index);
// The EIA image pixel (column from the left, row from the top) of a ray.
PixelCoord eiaPixel(const EiLayout& L, const RayAddress& a);
// The panel pixel: the EIA pixel offset by (panelCol0, panelRow0).
PixelCoord panelPixel(const EiLayout& L, const RayAddress& a);
// The inverse maps; nullopt for pixels outside every EI (toed-in gaps, panel border).
std::optional<RayAddress> addressAtEiaPixel(const EiLayout& L, PixelCoord p);
std::optional<RayAddress> addressAtPanelPixel(const EiLayout& L, PixelCoord p);

}  // namespace inim
