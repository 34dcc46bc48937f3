#pragma once
// The panel's cover glass seen from the lenslets. The view simulation refracts every ray
// through a plate of thickness t and index n on the emitting plane; seen through it, the panel
// sits t (1 - 1/n) nearer the lenslets, at the optical gap g_eff = g - t (1 - 1/n) (paraxial).
// The pinhole synthesis (rays in air at g) does not see the glass; predictions must.
#include <string>

#include "display/display.h"

namespace inim {

struct CoverGlassOptics {
  bool present = false;
  double thicknessMm = 0.0;
  double n = 1.0;  // at the wavelength asked for
  std::string material;
  // The optical gap of a panel at physical gap g seen through the glass (g itself without glass).
  double opticalGap(double g) const { return g - thicknessMm * (1.0 - 1.0 / n); }
};

// The display's cover glass at `lambdaNm` (present = false when the panel has none).
CoverGlassOptics coverGlassOptics(const Display& d, float lambdaNm = 550.0f);

}  // namespace inim
