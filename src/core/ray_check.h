#pragma once
// The door of the ray tracer: what every ray must be before it is traced.
#include <string>

#include "core/geometry.h"

namespace inim {

// Every ray that reaches the ray tracer, from any source (generated, a ray file, a ray table,
// an SDF, a placement's transform), passes this door: finite, a unit direction within 1e-6,
// and an origin within kMaxRayCoordinateMm of the display centre. Ten kilometres is far
// beyond any bench and far inside where single-precision traversal stays sound (huge finite
// values such as 2^63 trip the tracer's own assertions).
constexpr double kMaxRayCoordinateMm = 1e7;
constexpr double kUnitDirectionTolerance = 1e-6;
// InputError naming `file` and `where` (e.g. "row 12", "line 3") for a ray that fails the door.
void checkRay(const Vec3d& origin, const Vec3d& direction, const std::string& file, const std::string& where);

}  // namespace inim
