#pragma once
// The colours `inim calibrate` shows on the display (docs/colour-calibration.md):
//
//   ColorChecker  the 24-patch chart from measured spectral reflectances (BabelColor average,
//                 spectra/colorchecker_babelcolor_avg.csv) under D65: a scene's colours, with
//                 their spectra, so a camera sees them with its own metamerism;
//   drive grid    N^3 panel drive levels (0, 1/(N-1), ..., 1 per channel), the display
//                 characterisation set (as ArgyllCMS-style profiling sets), used to fit;
//   hold-out      colours never fitted, from a fixed seed: drawn uniformly from the panel's
//                 nominal gamut (drive cube), and separately from outside it (inside Rec.2020);
//   a CSV         name,X,Y,Z rows (field XYZ, D65 white Y = 1), for a user's own colours.
//
// Field colours are CIE 1931 XYZ in field units: the field's D65 white (a perfect diffuser
// under D65) has Y = 1. Patches of the drive grid carry their drive instead.
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "spectral/cie.h"
#include "spectral/spectrum.h"
#include "synthesis/panel_color.h"

namespace inim {

using Vec3d = glm::dvec3;

struct Patch {
  std::string name;
  Vec3d xyz{0.0};          // field colour (D65 white Y = 1); unused for drive patches
  SpectrumPtr radiance;    // the patch's radiance spectrum (white Y = 1), when it has one
  Vec3d drive{0.0};        // drive-grid patches: the drive shown
};

struct PatchSet {
  std::string name;        // "colorchecker", "grid", "holdout_in", "holdout_out", or the CSV's
  bool driveLevels = false;
  std::vector<Patch> patches;
};

// The 24 ColorChecker patches under D65 (reflectances extended as constants beyond the table's
// 380-730 nm). `path` "": spectra/colorchecker_babelcolor_avg.csv.
PatchSet colorCheckerPatches(const std::string& path = "");

// N^3 drive levels, red fastest. InputError (key grid_levels) for n < 2 or n > 17.
PatchSet driveGrid(int levels);

// `count` field colours whose exposed drive (exposure x native drive) is uniform in [0,1]^3:
// the panel's own gamut, from `seed`, keeping only colours a field in `fieldSpace` can hold
// (colour_chain.h representableInField; "spectral" holds all).
PatchSet holdOutInGamut(const PanelColor& panel, double exposure, int count, uint64_t seed,
                        const std::string& fieldSpace = "spectral");
// `count` field colours uniform in the linear Rec.2020 cube (white Y = 1) whose exposed drive
// lies outside [0,1]^3 by more than 1 %: colours the panel cannot show.
PatchSet holdOutOutOfGamut(const PanelColor& panel, double exposure, int count, uint64_t seed);

// A patch CSV: a header with the columns name, X, Y, Z (in that order, '#' comment lines
// allowed), then one row per patch. InputError naming the file, the line and the value for
// other columns, missing or non-finite values, or no rows.
PatchSet readPatchCsv(const std::string& path);

}  // namespace inim
