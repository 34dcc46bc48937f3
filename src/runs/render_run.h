#pragma once
// `inim render` as a library: a spectral image of a field (an analytic scene by default)
// through a pinhole or thin-lens camera, written as a linear EXR (R, G, B Rec.709, A, Z) and an
// sRGB PNG beside it. Errors name settings (spp, out, integrator, max_depth) before any work.
#include <optional>
#include <string>

#include "camera/fov_camera.h"
#include "field_render/renderer.h"
#include "scene/integrator.h"

namespace inim {

struct RenderRunSettings {
  std::string fieldPath;  // scene JSON or trained model; "": scenes/paper-fig7.json
  FovCameraSettings camera;
  RenderSettings render;
  // Integrator overrides of an analytic scene (a radiance field has none).
  std::optional<IntegratorSettings::Type> integrator;
  std::optional<int> maxDepth;
  std::string out;  // .exr
};

struct RenderRunResult {
  std::string fieldPath, png;
  RenderResult render;
};

RenderRunResult runRender(const RenderRunSettings& s);
// What was rendered, how fast, and the files written.
std::string renderText(const RenderRunSettings& s, const RenderRunResult& r);

// "x,y,z" -> a camera position or direction; InputError naming `key` (eye, look_at, up)
// unless it is three finite numbers.
Vec3 parseCameraVector(const std::string& text, const std::string& key);

}  // namespace inim
