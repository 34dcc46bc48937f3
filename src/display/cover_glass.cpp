#include "display/cover_glass.h"

#include "spectral/dispersion.h"

namespace inim {

CoverGlassOptics coverGlassOptics(const Display& d, float lambdaNm) {
  CoverGlassOptics c;
  if (!d.panel.coverGlass.has_value() || !(d.panel.coverGlass->thicknessMm > 0.0)) return c;
  c.present = true;
  c.thicknessMm = d.panel.coverGlass->thicknessMm;
  c.material = d.panel.coverGlass->material;
  c.n = double(MaterialCatalog::standard().dielectric(c.material)->n(lambdaNm));
  return c;
}

}  // namespace inim
