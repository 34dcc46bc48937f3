#include "synthesis/orthoscopic.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "core/ray_check.h"

namespace inim {

OrthoscopicQuery::OrthoscopicQuery(const Transform& fieldToDisplay, double vcpMm)
    : toDisplay_(fieldToDisplay), toField_(fieldToDisplay.inverse()), vcp_(vcpMm) {
  if (!std::isfinite(vcpMm)) throw InputError("", "vcp_mm", std::to_string(vcpMm), "a finite distance in mm");
}

OrthoscopicQuery::Query OrthoscopicQuery::make(const Point3d& pinhole, const Vec3d& d, uint64_t id,
                                               uint32_t sample) const {
  Query q;
  q.displayDir = -d;
  q.ray.id = id;
  q.ray.sample = sample;
  if (!(d.z > 0.0)) {  // parallel to the panel or pointing back: never reaches the VCP
    q.vcpPoint = pinhole;
    q.ray.o = Point3(toField_.point(pinhole));
    q.ray.d = Vec3(0.0f, 0.0f, -1.0f);
    q.ray.tNear = 0.0f;
    q.ray.tFar = -1.0f;
    return q;
  }
  q.vcpPoint = pinhole + d * (vcp_ / d.z);
  Vec3d df = toField_.vector(q.displayDir);
  double len = std::sqrt(glm::dot(df, df));  // field units per display mm along the ray
  q.displayPerField = 1.0 / len;
  const Point3d o = toField_.point(q.vcpPoint);
  if (!(std::max({std::abs(o.x), std::abs(o.y), std::abs(o.z)}) <= kMaxRayCoordinateMm && len > 0.0 &&
        std::isfinite(len)))  // the ray tracer's door (core/ray_check.h), checked here for the placement's sake
    throw InputError("", "placement",
                     formatText("display ray %llu starting at (%.6g, %.6g, %.6g) in the field", (unsigned long long)id,
                                o.x, o.y, o.z),
                     "a placement that keeps every query within 1e7 of the field's origin (its scale and translate_mm)");
  q.ray.o = Point3(o);
  q.ray.d = Vec3(df / len);
  q.ray.tNear = 0.0f;
  q.ray.tFar = kInfinity;
  return q;
}

}  // namespace inim
