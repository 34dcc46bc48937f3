#include "core/format.h"
#include "display/layout_override.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace inim {

EiLayoutKind parseLayoutKind(const std::string& s, const std::string& key) {
  if (s == "parallel") return EiLayoutKind::Parallel;
  if (s == "toed-in") return EiLayoutKind::ToedIn;
  if (s == "lens-grid") return EiLayoutKind::LensGrid;
  throw InputError("", key, "\"" + s + "\"", "parallel, toed-in or lens-grid");
}

EiLayout applyLayoutOverride(Display& d, const LayoutOverride& o) {
  if (o.viewingDistanceMm) {
    double D = *o.viewingDistanceMm;
    if (!(D > 0.0) || !std::isfinite(D)) {
      throw InputError("", o.distanceKey, formatNumber(D), "a viewing distance > 0 mm");
    }
    d.viewingDistanceMm = D;
  }
  if (o.layout) d.layout = parseLayoutKind(*o.layout, o.layoutKey);
  if (d.layout == EiLayoutKind::ToedIn && !d.viewingDistanceMm)
    throw InputError(d.file, o.distanceKey, "missing", "a viewing distance D for the toed-in layout");
  try {
    return computeLayout(d);
  } catch (const InputError& e) {
    // Name the setting when the override caused it.
    if (e.key() == "viewing_distance_mm" && (o.viewingDistanceMm || o.layout))
      throw InputError(d.file, o.viewingDistanceMm ? o.distanceKey : o.layoutKey, e.value(), e.expected());
    if (e.key() == "ei_count" && o.layout)
      throw InputError(d.file, "ei_count (with " + o.layoutKey + " " + *o.layout + ")", e.value(), e.expected());
    throw;
  }
}

}  // namespace inim
