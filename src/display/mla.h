#pragma once
// A microlens array of plano-convex lenslets, read from optics/mlas/*.json.
#include <optional>
#include <string>
#include <vector>

#include "core/json_config.h"

namespace inim {

// Wavelength of the helium d line, where focal lengths are quoted.
constexpr double kLambdaDNm = 587.56;

struct Mla {
  enum class Lattice { Square, Hex };
  enum class Aperture { Square, Circle, Hex };
  enum class Orientation { CurvedTowardViewer, CurvedTowardPanel };

  std::string name;
  std::string file;
  Lattice lattice = Lattice::Square;
  double pitchMm = 0.0;
  std::optional<double> radiusMm;       // vertex radius of curvature of the convex surface
  std::optional<double> focalLengthMm;  // as given in the file
  double conic = 0.0;
  Aperture aperture = Aperture::Square;
  double apertureMm = 0.0;              // side (square, hex flat-to-flat) or diameter; <= pitch
  double substrateThicknessMm = 0.0;    // flat substrate plus lens sag, see optics/README.md
  std::string material;                 // a dielectric of spectra/materials.json, e.g. "PMMA"
  Orientation orientation = Orientation::CurvedTowardViewer;
  std::vector<std::string> assumptions;
};

const char* latticeName(Mla::Lattice l);
const char* apertureName(Mla::Aperture a);
const char* orientationName(Mla::Orientation o);

// Paraxial focal length of the lenslets and where it came from.
struct LensletFocus {
  double focalLengthMm = 0.0;
  std::string source;                     // "focal_length_mm" or "radius_of_curvature_mm / (n_d - 1)"
  std::optional<double> indexD;           // n at 587.56 nm, when the material was looked up
  std::optional<double> focalFromRadiusMm;  // R / (n_d - 1), when R was given
};

// f = focal_length_mm when given, else R / (n_d - 1) with n_d from the material catalog.
// When both are given they must agree within 2 % (InputError naming the file otherwise).
LensletFocus lensletFocus(const Mla& m);

Mla loadMla(const std::string& path);
Mla parseMla(const JsonObject& o);

}  // namespace inim
