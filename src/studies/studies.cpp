#include "studies/studies.h"

#include "core/error.h"

namespace inim {

const StudyValue* StudyReport::find(const std::string& name) const {
  for (const auto& v : values)
    if (v.name == name) return &v;
  return nullptr;
}

std::vector<std::string> studyNames() {
  return {"flip-onset", "image-plane", "depth-sharpness", "braiding", "telecentric", "nerf-pipeline", "colour-calibration", "gap-tradeoff"};
}

StudyReport runStudy(const std::string& name, const StudyOptions& o) {
  if (name == "flip-onset") return runFlipOnset(o);
  if (name == "image-plane") return runImagePlane(o);
  if (name == "depth-sharpness") return runDepthSharpness(o);
  if (name == "braiding") return runBraiding(o);
  if (name == "telecentric") return runTelecentric(o);
  if (name == "nerf-pipeline") return runNerfPipeline(o);
  if (name == "colour-calibration") return runColourCalibration(o);
  if (name == "gap-tradeoff") return runGapTradeoff(o);
  std::string names;
  for (const auto& n : studyNames()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("", "study", name, "one of " + names);
}

}  // namespace inim
