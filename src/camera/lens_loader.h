#pragma once
// Lens prescriptions from files (optics/lenses/README.md describes both formats):
// - the pbrt-v4 lens format (.dat): rows "radius thickness index aperture" in mm, object side
//   first; index 0 or 1 = air, a row with radius 0 and index 0 is the aperture stop;
// - inim's JSON form (.json): surfaces with radius_mm, thickness_mm, conic, aperture_mm,
//   glass by catalog name / Sellmeier coefficients / n_d and V_d, an explicit orientation
//   and a thickness convention.
// Every problem is an InputError naming the file, the key (or line and column) and the value.
#include <optional>
#include <string>

#include "camera/lens_system.h"
#include "core/json_config.h"

namespace inim {

// "after": a row's thickness is the distance to the next surface (pbrt, Zemax);
// "before": the distance from the previous surface (the first row's value is ignored).
enum class ThicknessConvention { After, Before };
const char* thicknessConventionName(ThicknessConvention c);

// How glass of a pbrt file (which gives n_d only) disperses.
enum class PbrtDispersion {
  None,  // constant n = n_d: the default, since the designs are achromatised and one guessed
         // V_d for every element would add chromatic aberration the real lens does not have
  Abbe,  // two-term Cauchy through n_d with V_d = LensLoadOptions::abbeNumber for every glass
};

struct LensLoadOptions {
  // Overrides the file's own convention (pbrt directive "# thickness_convention: before",
  // JSON key "thickness_convention"); default: what the file says, else "after".
  std::optional<ThicknessConvention> thicknessConvention;
  PbrtDispersion pbrtDispersion = PbrtDispersion::None;
  double abbeNumber = 50.0;  // used with PbrtDispersion::Abbe
};

// The visible band a camera lens is used over (the display's primaries emit within it).
constexpr double kLensVisibleMinNm = 380.0, kLensVisibleMaxNm = 780.0;

// A lens by file path (.json, .zmx or .dat; relative paths through dataPath) or by catalog name
// under optics/lenses/ (name.json, then name.zmx, then name.dat). The result is validated, and
// its design().warnings name any catalogue glass used beyond the wavelengths its data cover.
LensSystem loadLens(const std::string& pathOrName, const LensLoadOptions& opt = {});
// The file a name or path refers to; InputError naming `context` and `key` if none exists.
std::string resolveLensPath(const std::string& pathOrName, const std::string& contextFile = "",
                            const std::string& key = "lens");

// Adds a warning for each catalogue glass whose data do not cover the visible band and the
// lens's design wavelengths.
void addGlassRangeWarnings(LensSystem& lens);

// Parsers on text already read; `file` is used in messages. Both validate.
LensSystem parsePbrtLens(const std::string& text, const std::string& file, const LensLoadOptions& opt = {});
LensSystem parseLensJson(const JsonObject& o, const LensLoadOptions& opt = {});

// Writes a lens back in the pbrt format (after convention, n_d per glass, 0 for air), with
// its name as the first comment. Used by tests and to export JSON lenses to pbrt.
std::string lensToPbrtText(const LensSystem& lens);

}  // namespace inim
