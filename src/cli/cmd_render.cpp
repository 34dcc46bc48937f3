// inim render: a spectral image of a field (an analytic scene by default) through a
// pinhole or thin-lens camera. Writes the linear EXR (R,G,B Rec.709, A, Z) and an sRGB PNG
// beside it. The run is src/runs/render_run.h.
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/options.h"
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
    CLI::Option* maxDepthOpt = nullptr;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  addSetting(cmd, "field", o->s.fieldPath, "--scene");
  addSetting(cmd, "out", o->s.out)->required();
  addSetting(cmd, "width", o->s.camera.width);
  addSetting(cmd, "height", o->s.camera.height);
  addSetting(cmd, "spp", o->s.render.spp);
  const ViewingPose& pose = o->s.camera.pose;
  addSetting(cmd, "eye", o->eye)->default_str(vectorText(pose.eye));
  addSetting(cmd, "look_at", o->lookAt)->default_str(vectorText(pose.lookAt));
  addSetting(cmd, "up", o->up)->default_str(vectorText(pose.up));
  addSetting(cmd, "fov", o->s.camera.hfovDeg);
  addSetting(cmd, "aperture", o->s.camera.apertureMm);
  addSetting(cmd, "focus", o->s.camera.focusDistanceMm);
  addSetting(cmd, "integrator", o->integrator);
  o->maxDepthOpt = addSetting(cmd, "max_depth", o->maxDepth);
  addRunOptions(cmd, o->run, [o] {
    RenderRunSettings& s = o->s;
    if (o->eye) s.camera.pose.eye = parseCameraVector(*o->eye, "eye");
    if (o->lookAt) s.camera.pose.lookAt = parseCameraVector(*o->lookAt, "look_at");
    if (o->up) s.camera.pose.up = parseCameraVector(*o->up, "up");
    if (o->integrator == "direct") s.integrator = IntegratorSettings::Type::Direct;
    if (o->integrator == "path") s.integrator = IntegratorSettings::Type::Path;
    if (o->maxDepthOpt->count()) s.maxDepth = o->maxDepth;
    o->run.applySeed(s.render.seed);
    const RenderRunResult r = runRender(s);
    std::printf("%s", renderText(s, r).c_str());
  });
}

}  // namespace inim::cli
