#pragma once
// `inim triads export | form` as a library: the RGB-wavelength triads of an EIA written as a
// Zemax SDF source file (3 monochromatic rays per display ray), and an EIA formed from such a
// file on a detector at the panel plane, as the paper's NSC step did. See src/triads/triads.h.
// Errors name settings (out, png, flux_scale, gap_mm) before any output.
#include <optional>
#include <string>

#include "display/layout_override.h"
#include "triads/triads.h"

namespace inim {

struct TriadExportSettings {
  std::string displayPath;  // "": the paper's prototype
  LayoutOverride layout;
  std::string eiaPath;      // EXR of drive values, panel- or EIA-sized
  std::string out;          // .sdf or .dat
  std::string wavelengths = "panel";
  TriadOptions options;     // its description is set by the run
};

struct TriadExportResult {
  uint64_t triads = 0, displayRays = 0;
  TriadWavelengths wavelengths;
};

TriadExportResult exportTriads(const TriadExportSettings& s);
std::string exportText(const TriadExportSettings& s, const TriadExportResult& r, double seconds);

struct TriadFormSettings {
  std::string displayPath;  // "": the paper's prototype
  LayoutOverride layout;
  std::optional<double> gapMm;  // detector at z = -gap; default: the display's generation gap
  std::string sdfPath;
  std::string out, png;         // EXR at the panel resolution; optional encoded PNG
  std::string wavelengths = "panel";
};

struct TriadFormResult {
  int width = 0, height = 0;
  uint64_t binned = 0, missed = 0, unknownWavelength = 0;
  TriadWavelengths wavelengths;
};

TriadFormResult formTriads(const TriadFormSettings& s);
std::string formText(const TriadFormSettings& s, const TriadFormResult& r, double seconds);
// A warning line when some rays carry none of the triad wavelengths; else "".
std::string formWarning(const TriadFormResult& r);

}  // namespace inim
