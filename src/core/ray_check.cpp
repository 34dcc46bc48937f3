#include "core/ray_check.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/format.h"

namespace inim {

void checkRay(const Vec3d& o, const Vec3d& d, const std::string& file, const std::string& where) {
  const bool finite = std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(d.x) &&
                      std::isfinite(d.y) && std::isfinite(d.z);
  const double reach = std::max({std::abs(o.x), std::abs(o.y), std::abs(o.z)});
  const char* expected = !finite ? "finite origin and direction"
                         : std::abs(glm::length(d) - 1.0) > kUnitDirectionTolerance
                             ? "a unit direction (length 1 within 1e-6)"
                         : reach > kMaxRayCoordinateMm ? "an origin within 1e7 mm (10 km) of the display centre"
                                                       : nullptr;
  if (!expected) return;
  throw InputError(file, where,
                   formatText("origin (%.9g, %.9g, %.9g), direction (%.9g, %.9g, %.9g)", o.x, o.y, o.z, d.x, d.y, d.z),
                   expected);
}

}  // namespace inim
