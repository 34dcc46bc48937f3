#pragma once
// The paper's Zemax model, written out (its Fig. 6): a non-sequential OpticStudio file holding
// a Source File object that reads the triad SDF and a Detector Color sized and pixelled as the
// EIA on the panel, at the gap the display gives, with as many analysis rays as the SDF holds.
// Its structure follows the paper's own NSC demo (lrio-copl/NERF-ZEMAX,
// EIA_generation_NSC_NERF_SDF.zmx; tests/data/zmx/nsc/): MODE NSC, the objects inside surface
// 1 (TYPE NONSEQCO, the stop), one NSOH line then NOID, NSOP and NSOD per object, UTF-16 with
// its byte-order mark and CRLF, as OpticStudio writes it.
//
// Not written: the lens array. No public OpticStudio file with a lenslet-array object could be
// found to confirm its parameters, and the paper's own model has none either (its rays leave the
// pinholes already, so the array is in the SDF); the file says so in a NOTE line. The objects'
// property settings (coatings, scattering, drawing) are left at OpticStudio's defaults.
#include <array>
#include <cstdint>
#include <string>

namespace inim {

struct EiLayout;

struct ZemaxNscModel {
  std::string name;               // NAME line
  std::string sourceFile;         // the SDF's file name, as the source object's comment
  uint64_t analysisRays = 0;      // the SDF's ray count: every ray is traced once
  uint64_t layoutRays = 1875;     // drawn in the layout plot (the demo's number)
  std::array<double, 3> wavelengthsUm{};  // the triads' R, G, B
  double detectorHalfWidthMm = 0.0, detectorHalfHeightMm = 0.0;
  int detectorPixelsX = 0, detectorPixelsY = 0;
  double detectorZMm = 0.0;       // the panel plane: -gap (the rays leave z = 0 toward -z)
};

// The model for the EIA of layout `L` exported as `sdfFile` with `triadRays` rays.
ZemaxNscModel zemaxNscModelFor(const EiLayout& L, const std::string& sdfFile, uint64_t triadRays,
                               const std::array<double, 3>& wavelengthsNm, const std::string& displayName);
// The file's text, lines ending in CRLF (ASCII).
std::string zemaxNscModelText(const ZemaxNscModel& m);
// Writes it as OpticStudio does: UTF-16 little endian with its byte-order mark.
void writeZemaxNscModel(const std::string& path, const ZemaxNscModel& m);

}  // namespace inim
