#include "studies/studies.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "display/display.h"
#include "studies/study_common.h"

namespace inim {

const StudyValue* StudyReport::find(const std::string& name) const {
  for (const auto& v : values)
    if (v.name == name) return &v;
  return nullptr;
}

std::vector<std::string> studyNames() {
  return {"flip-onset", "image-plane", "depth-sharpness", "braiding", "telecentric", "nerf-pipeline"};
}

StudyReport runStudy(const std::string& name, const StudyOptions& o) {
  // The studies sample lenslet cells and EIs as squares (the paper's MLA).
  if (!o.displayPath.empty()) {
    const Display d = loadDisplay(o.displayPath);
    if (d.mla.lattice != Mla::Lattice::Square)
      throw InputError(o.displayPath, "mla.lattice", "\"hex\"", "a square-lattice display (the studies sample square cells)");
  }
  if (name == "flip-onset") return runFlipOnset(o);
  if (name == "image-plane") return runImagePlane(o);
  if (name == "depth-sharpness") return runDepthSharpness(o);
  if (name == "braiding") return runBraiding(o);
  if (name == "telecentric") return runTelecentric(o);
  if (name == "nerf-pipeline") return runNerfPipeline(o);
  std::string names;
  for (const auto& n : studyNames()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("", "study", name, "one of " + names);
}

namespace study_detail {

StudyValue compare(const std::string& name, double measured, double predicted, double tolerance) {
  StudyValue v{name, measured, predicted, tolerance, false};
  v.pass = std::isfinite(measured) && std::abs(measured - predicted) <= tolerance * std::abs(predicted);
  return v;
}

std::string reproduceCommand(const std::string& study, const StudyOptions& o) {
  std::string c = "inim study " + study + " --out " + (o.outDir.empty() ? std::string("DIR") : o.outDir);
  if (!o.displayPath.empty()) c += " --display " + o.displayPath;
  if (o.quick) c += " --quick";
  return c;
}

std::string fmt(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

std::string valuesTable(const std::vector<StudyValue>& v, const std::string& unit) {
  std::string s = "| quantity | measured (" + unit + ") | predicted (" + unit + ") | error | tolerance | pass |\n";
  s += "|---|---|---|---|---|---|\n";
  for (const auto& x : v) {
    const double err = x.predicted != 0.0 ? (x.measured - x.predicted) / std::abs(x.predicted) : 0.0;
    s += "| " + x.name + " | " + fmt(x.measured, 3) + " | " + fmt(x.predicted, 3) + " | " + fmt(100.0 * err, 2) +
         "% | ±" + fmt(100.0 * x.tolerance, 0) + "% | " + (x.pass ? "yes" : "**no**") + " |\n";
  }
  return s;
}

bool allPass(const std::vector<StudyValue>& v) {
  for (const auto& x : v)
    if (!x.pass) return false;
  return !v.empty();
}

std::string verdictLine(const std::vector<StudyValue>& v) {
  int fails = 0;
  for (const auto& x : v) fails += x.pass ? 0 : 1;
  if (fails == 0) return "**PASS**: every quantity is within its tolerance.";
  return "**FAIL**: " + std::to_string(fails) + " of " + std::to_string(v.size()) +
         " quantities are outside their tolerance.";
}

}  // namespace study_detail
}  // namespace inim
