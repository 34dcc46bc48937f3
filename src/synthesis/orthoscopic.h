#pragma once
// The orthoscopic query (docs/design.md): every display ray is reversed. It
// starts on the virtual camera plane (VCP) z = D_VCP, on the display ray itself
// (o = pinhole + d * D_VCP / d.z), and goes into the scene along -d. The VCP is the near
// clipping plane: the query interval starts there (t = 0), so whatever lies closer to the
// viewer than the VCP (z > D_VCP) is not seen. Since the query ray retraces the light that
// the display ray will carry toward the viewer, the first surface it meets is the one the
// viewer sees: depth is never inverted, and the scene may lie in front of the MLA (real
// image), behind it (virtual image), or both.
//
// The field sits in the display frame through a placement (field/placement.h), so each
// query ray is taken into the field frame by the inverse placement. Field rays have unit
// directions in the field frame; `tScale` converts field distances back to display mm.
#include <cstdint>

#include "core/geometry.h"
#include "core/transform.h"
#include "field/field.h"

namespace inim {

class OrthoscopicQuery {
 public:
  // `fieldToDisplay`: the placement transform; `vcpMm`: D_VCP (finite, any sign).
  OrthoscopicQuery(const Transform& fieldToDisplay, double vcpMm);

  struct Query {
    FieldRay ray;        // in the field frame: unit direction, tNear = 0 on the VCP
    double displayPerField = 1.0;  // display mm per field unit along this ray
    Point3d vcpPoint{0.0};         // the ray's start on the VCP, display frame
    Vec3d displayDir{0.0};         // -d, display frame (unit)
  };
  // The query for display ray (pinhole o on z = 0, unit direction d with d.z > 0).
  // A display ray with d.z <= 0 never reaches the VCP: the query ray gets tFar = -1 (empty
  // interval), which every field answers with nothing.
  Query make(const Point3d& pinhole, const Vec3d& d, uint64_t id, uint32_t sample) const;

  // The display z (mm) of the first surface at field distance `fieldT` along query `q`.
  static double hitZ(const Query& q, double fieldT) {
    return q.vcpPoint.z + fieldT * q.displayPerField * q.displayDir.z;
  }
  static Point3d hitPoint(const Query& q, double fieldT) {
    return q.vcpPoint + fieldT * q.displayPerField * q.displayDir;
  }

  double vcpMm() const { return vcp_; }
  const Transform& fieldToDisplay() const { return toDisplay_; }

 private:
  Transform toDisplay_, toField_;
  double vcp_;
};

}  // namespace inim
