#pragma once
// A display panel: its pixel grid, primaries (emission spectra), transfer function, optional
// cover glass and subpixel layout, read from optics/panels/*.json (format: optics/README.md).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/json_config.h"
#include "spectral/spectrum.h"

namespace inim {

// Channel order everywhere in this stage: 0 = R, 1 = G, 2 = B.
constexpr int kNumPrimaries = 3;
const char* channelName(int channel);  // "R", "G", "B"

// The emission spectrum of one primary: a documented Gaussian placeholder or a CSV column.
struct PrimarySpec {
  enum class Kind { Gaussian, Csv };
  Kind kind = Kind::Gaussian;
  double meanNm = 0.0, fwhmNm = 0.0;  // Gaussian
  std::string csvPath, csvColumn;     // Csv (path already resolved against the panel file)
  double scale = 1.0;                 // relative power of this primary at drive value 1
};

// Builds the spectrum (needs the spectral stage; reads the CSV for Kind::Csv).
SpectrumPtr primarySpectrum(const PrimarySpec& p);
// Wavelength of the maximum: the Gaussian mean, or the CSV table's arg-max.
double primaryPeakNm(const PrimarySpec& p);

// Electro-optical transfer function: encoded panel value <-> linear drive value, both [0, 1].
struct Eotf {
  enum class Kind { Linear, SRGB, Gamma };
  Kind kind = Kind::SRGB;
  double gamma = 2.2;  // Kind::Gamma only
  double decode(double encoded) const;  // encoded -> linear
  double encode(double linear) const;   // linear -> encoded
  std::string name() const;             // "linear", "sRGB", "gamma 2.2"
};

struct CoverGlass {
  double thicknessMm = 0.0;
  std::string material;  // a name in spectra/materials.json (resolved by later stages)
};

// One emitting subpixel: a polygon in tile coordinates (units of pixels, origin at the tile's
// top-left corner, u right, v down, like image rows).
struct Subpixel {
  int channel = 0;
  std::vector<std::array<double, 2>> polygon;
};

// The subpixel geometry repeats every tileW x tileH pixels. Everything outside the polygons
// is black matrix. Parsed and stored here; the reconstruction stage uses it.
struct SubpixelLayout {
  std::string type = "rgb-stripe";  // "rgb-stripe", "diamond", "custom"
  int tileW = 1, tileH = 1;
  double fillFactor = 0.8;          // presets only
  std::vector<Subpixel> subpixels;
  double emittingArea(int channel) const;  // total polygon area of a channel, px^2 per tile
};
// Presets, built in code (documented in optics/README.md).
SubpixelLayout rgbStripeLayout(double fillFactor, const std::string& order = "RGB");
SubpixelLayout diamondLayout(double fillFactor);

struct Panel {
  std::string name;
  std::string file;  // where it was read from ("" if inline)
  int widthPx = 0, heightPx = 0;
  double pixelPitchMm = 0.0;
  std::array<PrimarySpec, kNumPrimaries> primaries;
  double peakLuminanceCdM2 = 0.0;
  Eotf eotf;
  std::string angularProfile = "lambertian";  // "lambertian" or "uniform"
  std::optional<CoverGlass> coverGlass;
  SubpixelLayout subpixels;
  std::vector<std::string> assumptions;

  double widthMm() const { return widthPx * pixelPitchMm; }
  double heightMm() const { return heightPx * pixelPitchMm; }
};

// Reads and validates a panel description (strict: unknown keys are errors).
Panel loadPanel(const std::string& path);
Panel parsePanel(const JsonObject& o);

// Reads an optional "assumptions" array of strings (shared by panel, MLA and display files).
std::vector<std::string> readAssumptions(const JsonObject& o);

}  // namespace inim
