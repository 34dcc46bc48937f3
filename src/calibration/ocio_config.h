#pragma once
// Exports a correction for OpenColorIO: a copy of the project's config with one more colour
// space whose transform reads the exported LUT file, written beside it.
#include <array>
#include <optional>
#include <string>

#include "calibration/lut3d.h"
#include "core/output_file.h"

namespace inim {

// Which way the LUT goes: FromReference makes converting reference -> the new space apply the
// LUT (a LUT from desired colour to panel drive); ToReference the other way.
enum class LutDirection { FromReference, ToReference };

struct OcioColourSpaceSettings {
  std::string name = "panel_calibrated";
  std::string description = "Colour-corrected panel drive (inim calibration LUT)";
  std::string lutFile;  // a file name beside the config, found through search_path "."
  LutDirection direction = LutDirection::FromReference;
  // FromReference only: the matrix taking the config's reference (linear Rec.709) to the LUT's
  // input, the panel's native drive (row-major 3x3; with the exposure and white gains inim
  // drives the panel with). Absent: the LUT reads reference values as they are.
  std::optional<std::array<double, 9>> referenceToLutInput;
  // FromReference only: clamp the LUT's output to [0, 1], as the panel (and inim) does: a
  // correction may ask for more than full drive, which no panel shows.
  bool clampOutput = true;
};

// Writes `configPath`: the config at `baseConfigPath` (empty: the config ColorSystem uses,
// spectra/ocio/config.ocio unless $OCIO) plus the colour space, validated by OpenColorIO.
// Throws InputError when the base config cannot be read or already has a space of that name.
void writeOcioConfig(const std::string& configPath, const OcioColourSpaceSettings& space,
                     const std::string& baseConfigPath = "");

enum class LutFormat { Cube, Clf };

struct CalibrationFiles {
  std::string cube, clf, config;
};

// Writes <folder>/<stem>.cube, <folder>/<stem>.clf and <folder>/<stem>.ocio, whose colour space
// reads the file in `configFormat`; all three are written or none (through OutputSet).
// space.lutFile is set here.
// The same into `outputs` (committed by the caller with its other outputs).
CalibrationFiles exportCalibration(OutputSet& outputs, const std::string& folder, const std::string& stem,
                                   const Lut3d& lut, OcioColourSpaceSettings space,
                                   LutFormat configFormat = LutFormat::Clf, const std::string& baseConfigPath = "");
CalibrationFiles exportCalibration(const std::string& folder, const std::string& stem, const Lut3d& lut,
                                   OcioColourSpaceSettings space, LutFormat configFormat = LutFormat::Clf,
                                   const std::string& baseConfigPath = "");

}  // namespace inim
