// inim render: a spectral image of a field (an analytic scene by default) through a
// pinhole or thin-lens camera. Writes the linear EXR (R,G,B Rec.709, A, Z) and an sRGB PNG
// beside it. The run is src/runs/render_run.h.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/format.h"
#include "runs/render_run.h"

namespace inim::cli {

namespace {

// "x,y,z" as --eye takes it.
std::string vectorText(const Vec3d& v) {
  return formatNumber(v.x) + "," + formatNumber(v.y) + "," + formatNumber(v.z);
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  struct Opts {
    RenderRunSettings s;
    std::optional<std::string> eye, lookAt, up;  // absent: the camera settings' pose
    std::string integrator;
    int maxDepth = 0;
    RunOptions run;
    CLI::Option *focusOpt = nullptr, *maxDepthOpt = nullptr;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("--scene,--field", o->s.fieldPath,
                  "Scene JSON, a trained radiance field (.inimrf) for novel views in its own units and frame, "
                  "or Gaussian splats (.ply, .splat; placed in the display frame) (default: scenes/paper-fig7.json)");
  cmd->add_option("--out", o->s.out, "Output EXR (linear Rec.709 + A + Z); an sRGB PNG is written beside it")
      ->required();
  cmd->add_option("--width", o->s.camera.width, "Image width, pixels")->capture_default_str();
  cmd->add_option("--height", o->s.camera.height, "Image height, pixels")->capture_default_str();
  cmd->add_option("--spp", o->s.render.spp, "Samples per pixel")->capture_default_str();
  const ViewingPose& pose = o->s.camera.pose;
  cmd->add_option("--eye", o->eye, "Camera position x,y,z in mm (display frame)")->default_str(vectorText(pose.eye));
  cmd->add_option("--look-at", o->lookAt, "Point the camera looks at, mm")->default_str(vectorText(pose.lookAt));
  cmd->add_option("--up", o->up, "Up vector")->default_str(vectorText(pose.up));
  cmd->add_option("--fov", o->s.camera.hfovDeg, "Horizontal field of view, degrees")->capture_default_str();
  cmd->add_option("--aperture", o->s.camera.apertureMm, "Thin-lens aperture diameter, mm (0 = pinhole)")
      ->capture_default_str();
  o->focusOpt = cmd->add_option("--focus", o->s.camera.focusDistanceMm, "Focus distance, mm (default: eye to look-at)");
  cmd->add_option("--integrator", o->integrator, "direct (default in scenes) or path (NEE + MIS)")
      ->check(CLI::IsMember({"direct", "path"}));
  o->maxDepthOpt = cmd->add_option("--max-depth", o->maxDepth, "Maximum scattering depth (overrides the scene)");
  addRunOptions(cmd, o->run, [o] {
    RenderRunSettings& s = o->s;
    if (o->eye) s.camera.pose.eye = parseCameraVector(*o->eye, "eye");
    if (o->lookAt) s.camera.pose.lookAt = parseCameraVector(*o->lookAt, "look_at");
    if (o->up) s.camera.pose.up = parseCameraVector(*o->up, "up");
    if (o->integrator == "direct") s.integrator = IntegratorSettings::Type::Direct;
    if (o->integrator == "path") s.integrator = IntegratorSettings::Type::Path;
    // Given on the command line, 0 is not "the default" (the camera's own meaning of 0).
    const float focus = s.camera.focusDistanceMm;
    if (o->focusOpt->count() && !(focus > 0.0f && std::isfinite(focus)))
      throw InputError("", "focus_distance_mm", formatNumber(focus), "a focus distance > 0 mm");
    if (o->maxDepthOpt->count()) {
      if (o->maxDepth < 0 || o->maxDepth > 1000)  // the scene file's range (scene_loader.cpp)
        throw InputError("", "max_depth", std::to_string(o->maxDepth), "a scattering depth in 0-1000");
      s.maxDepth = o->maxDepth;
    }
    o->run.applySeed(s.render.seed);
    const RenderRunResult r = runRender(s);
    std::printf("rendered %s: %dx%d, %d spp, %.2f s, %.2f Mrays/s (camera rays)\n  wrote %s\n  wrote %s\n",
                r.fieldPath.c_str(), s.camera.width, s.camera.height, s.render.spp, r.render.seconds,
                r.render.raysTraced / r.render.seconds * 1e-6, s.out.c_str(), r.png.c_str());
  });
}

}  // namespace inim::cli
