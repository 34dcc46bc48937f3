#pragma once
// Where the field sits in the display frame (docs/design.md): a placement transform
// field -> display, display = T(translate) * R(rotate) * S(scale) * field. It lives beside the
// Field interface because every stage that places a field uses it: EIA synthesis, the
// reference view, a trained model's default placement (fitting).
//
// `scale` is display millimetres per field unit (per axis, or uniform). A trained radiance
// field lives in its own units: the paper placed its NeRF at 0.0075 field units per mm, i.e.
// scale = 1 / 0.0075 = 133.3 mm per field unit; run files may give it that way too
// ("field_units_per_mm"). Analytic scenes are already in mm (scale 1).
//
// The transform decides which parts of the scene are real images (z > 0, in front of the MLA)
// and which are virtual (z < 0, behind it).
#include <cstdint>
#include <optional>
#include <string>

#include "core/geometry.h"
#include "core/transform.h"

namespace inim {

struct Placement {
  Vec3d scale{1.0, 1.0, 1.0};      // display mm per field unit, per axis
  Vec3d rotateDeg{0.0, 0.0, 0.0};  // about x, then y, then z (R = Rz Ry Rx), degrees
  Vec3d translateMm{0.0, 0.0, 0.0};
  // Where the values came from ("command line", the run file or the model), for error
  // messages: settings given one by one are named by their keys (scale, rotate_deg,
  // translate_mm), a run file's by the file and its key path (placement.scale).
  std::string source = "command line";
  std::string scaleKey = "scale";

  // The field -> display transform. InputError naming `source` and the scale key when the
  // scale is singular (a zero or non-finite factor) or any value is not finite.
  Transform toDisplay() const;
  bool isIdentity() const;
  std::string describe() const;  // "scale 1, rotate (0, 0, 0) deg, translate (0, 0, 0) mm"
};

// Placement values given one by one (absent = keep the base's).
struct PlacementOverride {
  std::optional<Vec3d> scale, rotateDeg, translateMm;
};
// `base` (a run file's placement, or a trained field's own; the defaults when absent) with the
// override applied. The transform is checked here, before any work (a singular placement is an
// InputError naming the setting that made it).
Placement resolvePlacement(const std::optional<Placement>& base, const PlacementOverride& given);

class Field;
// The field's bounds carried into another frame (the display's): the box around their eight
// corners. False, leaving lo and hi as they were, when the field's bounds are unknown.
bool boundsInFrame(const Field& field, const Transform& fieldToFrame, Point3d& lo, Point3d& hi);

// Parses "x,y,z" (or one number when `allowScalar`, meaning x = y = z), as settings are
// written on the command line; InputError naming `key` otherwise.
Vec3d parseVec3(const std::string& text, const std::string& key, bool allowScalar = false);
// A placement given as text, "" where not given: scale "S" or "sx,sy,sz", rotation "rx,ry,rz"
// (degrees), translation "x,y,z" (mm); InputError naming the setting: `prefix` + scale,
// rotate_deg or translate_mm.
PlacementOverride parsePlacementOverride(const std::string& scale, const std::string& rotateDeg,
                                         const std::string& translateMm, const std::string& prefix = "");

}  // namespace inim
