#include "triads/zemax_nsc_model.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <filesystem>
#include <fstream>

#include "core/text_encoding.h"
#include "display/ei_layout.h"

namespace inim {

namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12E", v);
  return buf;
}

// One numbered object parameter, with the solve columns the demo writes (none, scale 1).
std::string parameterLine(int k, double v) {
  return "  NSOD " + std::to_string(k) + " " + num(v) + " 0 0 1.000000000000E+00 0.000000000000E+00 0 \"\"";
}

// Position (x y z, tilts about x y z in degrees) and material, then the columns' solve data.
std::string placementLines(double z, const std::string& material) {
  std::string s = "  NSOP 0 0 " + num(z) + " 0 0 0" + (material.empty() ? "" : " " + material) + "\n";
  s += "  NSOV 0 0 0 0 0 0 0\n  NSOU 0 0 0 0 0 0 0 0 0 0 0 0\n  NSOW 0 0 0 0 0 0\n";
  s += "  NSOS 1 1 1 1 1 1\n  NSOO 0 0 0 0 0 0\n  NSOQ \"\" \"\" \"\" \"\" \"\" \"\"\n";
  return s;
}

std::string sourceObject(const ZemaxNscModel& m) {
  const double lo = std::min({m.wavelengthsUm[0], m.wavelengthsUm[1], m.wavelengthsUm[2]});
  const double hi = std::max({m.wavelengthsUm[0], m.wavelengthsUm[1], m.wavelengthsUm[2]});
  std::string s = "  NSOH NSC_SFIL 0 0 " + m.sourceFile + "\n  NOID 1\n" + placementLines(0.0, "");
  const double params[] = {double(m.layoutRays), double(m.analysisRays), 1.0, 0.0, 0.0, 0.0, 0.0, lo, hi};
  // 1 layout rays, 2 analysis rays, 3 power (W), 4 wavenumber (0: the file's), 5 colour,
  // 6 randomise (0: in file order), 7 power in file (OpticStudio fills it), 8-9 wavelength range.
  for (int k = 0; k < 9; ++k) s += parameterLine(k + 1, params[k]) + "\n";
  return s;
}

std::string detectorObject(const ZemaxNscModel& m) {
  std::string s = "  NSOH NSC_DETC 0 0 EIA on the panel\n  NOID 2\n" + placementLines(m.detectorZMm, "ABSORB");
  // 1-2 half width and height, 3-4 pixels, 6 colour mode 4 (true colour, as the demo), 12-15
  // accepted angles +-90 degrees.
  const double params[] = {m.detectorHalfWidthMm, m.detectorHalfHeightMm, double(m.detectorPixelsX),
                           double(m.detectorPixelsY), 0.0, 4.0, 0.0, 0.0, 0.0, 0.0, 0.0, -90.0, 90.0, -90.0, 90.0, 0.0, 0.0};
  for (int k = 0; k < 17; ++k) s += parameterLine(k + 1, params[k]) + "\n";
  return s;
}

std::string header(const ZemaxNscModel& m) {
  std::string s = "VERS 230724 3503 371314 371314\nMODE NSC\nNAME " + m.name + "\n";
  s += "NOTE 0 Written by inim: the paper's Fig. 6 model. The SDF named by object 1 goes in OpticStudio's\n";
  s += "NOTE 0 Objects\\Sources\\Source Files folder. The lens array is not an object here (its rays are in\n";
  s += "NOTE 0 the SDF already); the detector is the EIA on the panel, at the display's gap.\n";
  s += "UNIT MM X W X CM MR CPMM\nENPD 1\nGCAT SCHOTT MISC\nFTYP 0 1 1 3 1 0 0 1\nXFLN 0\nYFLN 0\nFWGN 1\n";
  for (int i = 0; i < 3; ++i) s += "WAVM " + std::to_string(i + 1) + " " + num(m.wavelengthsUm[size_t(i)]) + " 1\n";
  s += "PWAV 2\nNSCD 500 100 0 0.001 2000 1e-06 0 0 0 0 0 1 1000000 1 2\n";
  return s;
}

std::string withCrlf(const std::string& lf) {
  std::string out;
  out.reserve(lf.size() + lf.size() / 20);
  for (char c : lf) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return out;
}

}  // namespace

ZemaxNscModel zemaxNscModelFor(const EiLayout& L, const std::string& sdfFile, uint64_t triadRays,
                               const std::array<double, 3>& wavelengthsNm, const std::string& displayName) {
  ZemaxNscModel m;
  m.name = "inim EIA formation: " + displayName;
  m.sourceFile = std::filesystem::path(sdfFile).filename().string();
  m.analysisRays = triadRays;
  m.layoutRays = std::min<uint64_t>(m.layoutRays, triadRays);
  for (size_t i = 0; i < 3; ++i) m.wavelengthsUm[i] = wavelengthsNm[i] * 1e-3;
  // The EIA is centred on the display axis (triads.h's detector): pixel u at x = (u - W/2) p.
  m.detectorHalfWidthMm = 0.5 * L.eiaW * L.pixelMm;
  m.detectorHalfHeightMm = 0.5 * L.eiaH * L.pixelMm;
  m.detectorPixelsX = L.eiaW;
  m.detectorPixelsY = L.eiaH;
  m.detectorZMm = -L.gapMm;
  return m;
}

std::string zemaxNscModelText(const ZemaxNscModel& m) {
  std::string s = header(m);
  s += "SURF 0\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ INFINITY\n";
  s += "SURF 1\n  STOP\n  TYPE NONSEQCO\n  CURV 0.0 0 0 0 0 \"\"\n";
  for (int k = 0; k <= 9; ++k) s += "  PARM " + std::to_string(k) + " 0\n";
  s += sourceObject(m) + detectorObject(m);
  s += "  DISZ 0\nSURF 2\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ 0\n";
  return withCrlf(s);
}

void writeZemaxNscModel(const std::string& path, const ZemaxNscModel& m) {
  const std::string bytes = utf16leWithBom(zemaxNscModelText(m));
  std::ofstream out(path, std::ios::binary);
  if (!out.write(bytes.data(), std::streamsize(bytes.size())) || !out.flush())
    throw std::runtime_error("cannot write the Zemax model " + path);
}

}  // namespace inim
