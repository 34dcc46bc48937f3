#include "core/format.h"
#include "camera/camera_config.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/output_file.h"
#include "core/file_kinds.h"

namespace fs = std::filesystem;

namespace inim {

std::string defaultCameraPath() { return dataPath("optics/cameras/alvium-1800-u-500c.json"); }

CameraDescription loadCameraDescription(const std::string& s, const LensLoadOptions& lensOptions) {
  std::string path;
  if (s.find('/') != std::string::npos || isFileKind(s, FileKind::Json)) {
    path = dataPath(s);
  } else {
    path = dataPath("optics/cameras/" + s + ".json");
  }
  if (!fs::exists(path)) throw InputError(path, "", "\"" + s + "\"", "an existing camera file (not found)");
  Json j = readJsonFile(path);
  return parseCameraDescription(JsonObject(j, path, ""), lensOptions);
}

CameraDescription parseCameraDescription(const JsonObject& o, const LensLoadOptions& lensOptions) {
  CameraDescription c;
  c.file = o.file();
  c.name = o.string("name", fs::path(c.file).stem().string());
  const std::string model = o.choice("model", {"real-lens", "thin-lens", "pinhole"}, "real-lens");
  c.model = model == "pinhole" ? CameraModelKind::Pinhole
            : model == "thin-lens" ? CameraModelKind::ThinLens
                                   : CameraModelKind::RealLens;
  c.sensor = parseSensor(o.object("sensor"));

  const Json& lv = o.raw("lens");
  if (lv.is_object()) {
    c.lens = parseLensJson(o.object("lens"), lensOptions);
    c.lensSource = "(inline)";
  } else if (lv.is_string()) {
    c.lensSource = lv.get<std::string>();
    std::string path = resolveLensPath(c.lensSource, c.file, "lens");
    c.lens = loadLens(path, lensOptions);
    // What the lens file could only be read approximately travels with the camera's assumptions.
    for (const std::string& w : c.lens.design().warnings) c.assumptions.push_back("lens: " + w);
  } else {
    o.fail("lens", jsonValueText(lv), "a lens name in optics/lenses/, a lens file path, or an inline JSON lens");
  }

  if (o.has("f_number")) {
    c.fNumber = o.positive("f_number");
    const double widest = widestFNumber(c.lens);
    if (c.fNumber < widest * (1.0 - 1e-9))
      o.fail("f_number", formatNumber(c.fNumber), "an f-number >= " + formatNumber(widest) + " (the lens's widest aperture)");
  }
  c.distanceMm = o.positive("distance_mm", 350.0);
  if (o.has("focus_distance_mm")) {
    const Json& f = o.raw("focus_distance_mm");
    if (f.is_string() && f.get<std::string>() == "infinity") c.focusDistanceMm = std::numeric_limits<double>::infinity();
    else c.focusDistanceMm = o.positive("focus_distance_mm");
  }
  c.focusMode = o.choice("focus_mode", {"best-rms", "paraxial"}, "best-rms") == "paraxial" ? FocusMode::Paraxial
                                                                                          : FocusMode::BestRms;
  c.fresnel = o.boolean("fresnel", false);
  if (o.has("assumptions")) {
    const Json& a = o.raw("assumptions");
    if (!a.is_array()) o.fail("assumptions", jsonValueText(a), "an array of strings");
    for (const auto& e : a) {
      if (!e.is_string()) o.fail("assumptions", jsonValueText(a), "an array of strings");
      c.assumptions.push_back(e.get<std::string>());
    }
  }
  o.rejectUnknown();
  return c;
}

ViewingPose defaultViewingPose(const CameraDescription& c) {
  ViewingPose p;
  p.eye = {0.0, 0.0, c.distanceMm};
  p.lookAt = {0.0, 0.0, 0.0};
  p.up = {0.0, 1.0, 0.0};
  return p;
}

RealLensSettings realLensSettings(const CameraDescription& c, double focusMm) {
  RealLensSettings s;
  s.fNumber = c.fNumber;
  s.focusDistanceMm = focusMm;
  s.focusMode = c.focusMode;
  s.fresnel = c.fresnel;
  return s;
}

std::unique_ptr<CameraModel> makeCameraModel(const CameraDescription& c, const ViewingPose& pose,
                                             std::optional<CameraModelKind> kind) {
  const CameraModelKind k = kind.value_or(c.model);
  const double focus = c.focusDistanceMm > 0.0 ? c.focusDistanceMm : glm::length(pose.lookAt - pose.eye);
  if (k == CameraModelKind::RealLens) {
    return std::make_unique<RealLensCameraModel>(c.lens, c.sensor.geometry(), pose, realLensSettings(c, focus));
  }
  LensSystem lens = c.lens;
  if (c.fNumber > 0.0) setFNumber(lens, c.fNumber);
  const LensInfo info = analyzeLens(lens);
  auto thin = std::make_unique<ThinLensCameraModel>(c.sensor.geometry(), pose, info.eflMm, info.fNumber, focus);
  if (k == CameraModelKind::ThinLens) return thin;
  return std::make_unique<PinholeCameraModel>(c.sensor.geometry(), pose, thin->sensorDistanceMm());
}

}  // namespace inim
