#pragma once
// The run file: a run's placement and, optionally, its other settings, so a run can be
// repeated. Settings given one by one (the command line) override it:
//   {
//     "placement": {"scale": 1 | [sx, sy, sz] | "field_units_per_mm": 0.0075,
//                   "rotate_deg": [rx, ry, rz], "translate_mm": [x, y, z]},
//     "display": "file.json", "scene": "file.json",      (paths relative to the run file)
//     "vcp_mm": 100, "layout": "parallel", "viewing_distance_mm": 350, "spp": 4,
//     "exposure": 1 | "auto", "gamut": "clip" | "desaturate", "white_balance": "none" | "d65",
//     "triad_wavelengths": "panel" | "paper" | [656, 566, 471], "seed": 1,
//     "calibration": "file.cube" | "file.clf"            (relative to the run file)
//   }
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>

#include "display/layout_override.h"
#include "field/placement.h"

namespace inim {

// Settings a run file may carry (absent = not given; the command line or defaults decide).
struct RunFile {
  std::string file;
  std::optional<Placement> placement;
  std::optional<std::string> display, scene, calibration;  // resolved against the run file's folder
  std::optional<double> vcpMm, viewingDistanceMm;
  std::optional<std::string> layout, exposure, gamut, whiteBalance, triadWavelengths;
  std::optional<int> spp;
  std::optional<uint64_t> seed;
};

// Strict reader (unknown keys are errors naming the file and key).
RunFile loadRunFile(const std::string& path);

// The one rule for every command that takes a run file: defaults < run file < command line.
// A setting starts at its library default (its settings struct's initialiser, the only place
// a default is written); the run file's value replaces it, the command line's replaces both.
template <class T>
void resolveSetting(T& setting, const std::optional<std::type_identity_t<T>>& fromRunFile,
                    const std::optional<std::type_identity_t<T>>& given) {
  if (given) setting = *given;
  else if (fromRunFile) setting = *fromRunFile;
}
// The display settings given one by one (absent: not given).
struct DisplayGiven {
  std::optional<std::string> display, layout;
  std::optional<double> viewingDistanceMm;
};

// The EI layout settings: the command line's (absent: not given) over the run file's (`run` may
// be null), each named in messages by where it came from: its flag, or the run file's key.
LayoutOverride resolveLayout(const RunFile* run, const std::optional<std::string>& layout,
                             const std::optional<double>& viewingDistanceMm);
// For a setting given as text and parsed by the library (exposure, gamut, ...): the text that
// wins, or none (the default stands).
inline const std::optional<std::string>& chosenText(const std::optional<std::string>& fromRunFile,
                                                    const std::optional<std::string>& given) {
  return given ? given : fromRunFile;
}

}  // namespace inim
