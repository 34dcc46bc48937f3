#pragma once
// One check for every panel-to-MLA gap a user can give (a display's generation_gap_mm and
// reconstruction_gap_mm, --gap-mm of rays, eia, view and triads): finite and within the range a
// display can have. Below 1 µm a pixel's ray direction (x, y, g) loses its z component to
// rounding (a 1e-300 gap made rays parallel to the panel); beyond 10 m it is no longer a
// display. Whether a gap also fits a real MLA (the panel behind its flat face) is the MLA
// model's check.
//
//   checkGapMm(g, display.file, "reconstruction_gap_mm");   // throws InputError naming both
#include <string>

namespace inim {

constexpr double kMinGapMm = 1e-3, kMaxGapMm = 1e4;

// Returns `gapMm`; InputError(file, key, value, expected) when it is outside the range.
double checkGapMm(double gapMm, const std::string& file, const std::string& key);

}  // namespace inim
