#include "calibration/lut3d.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace inim {

Lut3d::Lut3d(int size) : size_(size) {
  if (size < 2 || size > 256)
    throw InputError("", "lut_size", std::to_string(size), "2 to 256 nodes per axis");
  values_.resize(size_t(size) * size * size);
  for (int b = 0; b < size; ++b)
    for (int g = 0; g < size; ++g)
      for (int r = 0; r < size; ++r) set(r, g, b, node(r, g, b));
}

Lut3d Lut3d::sample(const ColourFunction& f, int size) {
  Lut3d lut(size);
  for (int b = 0; b < size; ++b)
    for (int g = 0; g < size; ++g)
      for (int r = 0; r < size; ++r) lut.set(r, g, b, f(lut.node(r, g, b)));
  return lut;
}

Vec3d Lut3d::eval(const Vec3d& rgb) const {
  int cell[3];
  double f[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double x = std::clamp(rgb[axis], 0.0, 1.0) * double(size_ - 1);
    cell[axis] = std::min(int(x), size_ - 2);
    f[axis] = x - cell[axis];
  }
  auto corner = [&](int dr, int dg, int db) -> const Vec3d& { return at(cell[0] + dr, cell[1] + dg, cell[2] + db); };
  const Vec3d& c000 = corner(0, 0, 0);
  const Vec3d& c111 = corner(1, 1, 1);
  const double fr = f[0], fg = f[1], fb = f[2];
  // The tetrahedron containing the point is chosen by the order of the fractions; its
  // barycentric weights are differences of consecutive sorted fractions.
  if (fr > fg) {
    if (fg > fb) return (1 - fr) * c000 + (fr - fg) * corner(1, 0, 0) + (fg - fb) * corner(1, 1, 0) + fb * c111;
    if (fr > fb) return (1 - fr) * c000 + (fr - fb) * corner(1, 0, 0) + (fb - fg) * corner(1, 0, 1) + fg * c111;
    return (1 - fb) * c000 + (fb - fr) * corner(0, 0, 1) + (fr - fg) * corner(1, 0, 1) + fg * c111;
  }
  if (fb > fg) return (1 - fb) * c000 + (fb - fg) * corner(0, 0, 1) + (fg - fr) * corner(0, 1, 1) + fr * c111;
  if (fb > fr) return (1 - fg) * c000 + (fg - fb) * corner(0, 1, 0) + (fb - fr) * corner(0, 1, 1) + fr * c111;
  return (1 - fg) * c000 + (fg - fr) * corner(0, 1, 0) + (fr - fb) * corner(1, 1, 0) + fb * c111;
}

nlohmann::json Lut3d::parameters() const {
  nlohmann::json table = nlohmann::json::array();
  for (const Vec3d& v : values_) table.push_back({v.x, v.y, v.z});
  return {{"model", name()}, {"size", size_}, {"interpolation", "tetrahedral"},
          {"domain", {0.0, 1.0}}, {"order", "red fastest"}, {"table", table}};
}

}  // namespace inim
