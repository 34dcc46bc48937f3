#pragma once
// Validation studies (validation/<study>/): reproducible runs that measure a piece of physics
// out of the simulation, compare it with the analytic prediction and write a report folder:
// report.md (what, prediction, method, result table, verdict with tolerance, the command that
// reproduces it), *.png plots and the *.csv data behind them. Every file is written to a
// temporary and renamed into place only when the whole study succeeded (OutputSet).
#include <string>
#include <vector>

namespace inim {

struct StudyOptions {
  std::string outDir;       // output folder (created)
  std::string displayPath;  // display JSON; empty: the paper's prototype (defaultDisplayPath())
  bool quick = false;       // fewer depths, smaller images, fewer samples (the CI tests)
};

// One compared quantity of a study: against a prediction within a relative tolerance, or
// against a one-sided bound.
struct StudyValue {
  enum class Check { Relative, AtLeast, AtMost };
  std::string name;
  double measured = 0.0;
  double predicted = 0.0;  // the prediction; for a bound, the bound
  double tolerance = 0.0;  // Relative: pass when |measured - predicted| <= tolerance * |predicted|
  bool pass = false;
  Check check = Check::Relative;  // AtLeast: pass when measured >= predicted; AtMost: <=
};

struct StudyReport;
// Each value against its prediction, the files written and the verdict.
std::string studyReportText(const StudyReport& r);

struct StudyReport {
  std::string study;                // e.g. "flip-onset"
  std::vector<StudyValue> values;   // the verdict's quantities
  std::vector<std::string> files;   // files written (final paths)
  bool pass = false;                // every value within its tolerance
  const StudyValue* find(const std::string& name) const;
};

// `inim study flip-onset`: own-EI fraction against viewing angle, ideal and real MLA at the
// reconstruction gap; the 50% crossing against psi/2 = atan(P / 2g), within 10%.
StudyReport runFlipOnset(const StudyOptions& o);
// `inim study image-plane`: RMS bundle radius against z of a panel point traced through the
// real centre lenslet (g = 4 mm, paraxial and full aperture); the sharpest plane against
// H' + g f / (g - f), and the sharpest plane against the gap.
StudyReport runImagePlane(const StudyOptions& o);

// `inim study depth-sharpness`: a slanted edge at a sweep of depths, EIA synthesised at
// g = 4 mm, seen through the real and ideal MLA by a thin-lens camera focused on the target;
// the real MLA's depth of the largest edge MTF50 (and the centre of the band within 70% of it)
// against H' + g f / (g - f), within 25%.
StudyReport runDepthSharpness(const StudyOptions& o);
// `inim study braiding`: a point's EIA synthesised at several depths, seen by a pinhole eye
// scanned across the display through the ideal and the real MLA; per lenslet, the apparent
// position of the point against the eye position (facet lines): the facet-to-facet jump
// against P (1 - L/z) (D - z) / (D - L), zero at the reference image plane L.
StudyReport runBraiding(const StudyOptions& o);
// `inim study telecentric`: the reconstructed width of a bar seen from D = 350 mm, parallel
// against toed-in layout; parallel against the EI/lens pitch prediction, toed-in against the
// true width.
StudyReport runTelecentric(const StudyOptions& o);
// `inim study nerf-pipeline`: the paper's workflow on the analytic scene paper-fig7 against exact
// ground truth: synthetic capture -> trained voxel radiance field -> EIA -> view, each step
// compared with the same step done with the scene itself (PSNR, SSIM, CIEDE2000, depth);
// one-sided bounds on the held-out PSNR, the EIA and the view agreement.
StudyReport runNerfPipeline(const StudyOptions& o);

// `inim study colour-calibration`: the colour chain characterised, corrected and verified on
// hold-out colours for the placeholder and measured-OLED primaries and their mismatch; bounds
// on the in-gamut hold-out error at 0° after calibration (mean 1, p95 2, max 3 CIEDE2000).
StudyReport runColourCalibration(const StudyOptions& o);

// `inim study gap-tradeoff`: the panel-to-MLA gap swept around f (EIA made for each gap), inim
// fig11 with its error budget on the default scene and a depth ramp (parallel and toed-in layout):
// the main rungs and the error against depth per gap beside psi and L; the gap with the lowest
// error and why. Bounds: the ideal display no worse than the full chain beyond the noise floor, at
// every gap; the toed-in ramp's error lower near L than far from it.
StudyReport runGapTradeoff(const StudyOptions& o);

// `inim study architectures`: the catalogue's display architectures (today's MLA, double MLA,
// compound array, pinhole array, barrier MLA) through inim fig11 with their error budgets on the
// default scene: first order, budget, error against depth side by side, contact sheets, which
// suits which scene depth. Bound: for each, the ideal display no worse than the full chain
// beyond the noise floor.
StudyReport runArchitectures(const StudyOptions& o);

// The studies, in one table (studies.cpp): adding a study is its file, its run function
// declared above and a line in the table; `inim study --help` and the docs read the table.
struct StudyInfo {
  const char* name;     // "flip-onset": the command's argument and the folder under validation/
  const char* summary;  // one line
  StudyReport (*run)(const StudyOptions& o);
};
const std::vector<StudyInfo>& studies();
// The names of studies(), in order.
std::vector<std::string> studyNames();
// InputError for an unknown name.
StudyReport runStudy(const std::string& name, const StudyOptions& o);

}  // namespace inim
