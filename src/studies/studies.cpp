#include "studies/studies.h"

#include "core/format.h"
#include "core/error.h"

namespace inim {

const StudyValue* StudyReport::find(const std::string& name) const {
  for (const auto& v : values)
    if (v.name == name) return &v;
  return nullptr;
}

const std::vector<StudyInfo>& studies() {
  static const std::vector<StudyInfo> table = {
      {"flip-onset", "own-EI fraction against viewing angle; the flip against psi/2", runFlipOnset},
      {"image-plane", "a panel point traced through the real lenslet; the sharpest plane against H' + gf/(g-f)",
       runImagePlane},
      {"depth-sharpness", "a slanted edge's MTF50 against depth, real and ideal MLA", runDepthSharpness},
      {"braiding", "a point's facets seen by a scanning eye; the facet jump against depth", runBraiding},
      {"telecentric", "a bar's reconstructed width, parallel against toed-in layout", runTelecentric},
      {"nerf-pipeline", "capture, train, EIA and view of the default scene against the scene itself",
       runNerfPipeline},
      {"colour-calibration", "the colour chain characterised, corrected and verified on hold-out colours",
       runColourCalibration},
      {"gap-tradeoff", "the gap swept around f: error budget and error against depth per gap", runGapTradeoff},
      {"architectures", "the catalogue's display architectures compared: first order, budget, error against depth",
       runArchitectures},
  };
  return table;
}

std::vector<std::string> studyNames() {
  std::vector<std::string> names;
  for (const StudyInfo& s : studies()) names.push_back(s.name);
  return names;
}

StudyReport runStudy(const std::string& name, const StudyOptions& o) {
  for (const StudyInfo& s : studies())
    if (name == s.name) return s.run(o);
  std::string names;
  for (const auto& n : studyNames()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("", "study", name, "one of " + names);
}

std::string studyReportText(const StudyReport& r) {
  std::string t;
  for (const auto& v : r.values)
    t += formatText("%-55s measured %9.3f  predicted %9.3f  (tol %2.0f%%)  %s\n", v.name.c_str(), v.measured,
                    v.predicted, 100.0 * v.tolerance, v.pass ? "ok" : "FAIL");
  for (const auto& f : r.files) t += "wrote " + f + "\n";
  return t + r.study + ": " + (r.pass ? "PASS" : "FAIL") + "\n";
}

}  // namespace inim
