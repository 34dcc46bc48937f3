// inim capture: a posed synthetic dataset of an analytic scene (transforms.json + PNGs), like
// the smartphone scan of the paper's workflow, so scene -> capture -> train -> EIA -> view
// runs in software against exact ground truth. See src/runs/capture_run.h.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/capture_run.h"

namespace inim::cli {

void addCaptureCommand(CLI::App& app) {
  struct Opts {
    CaptureRunSettings s;
    double radius = 0;
    bool quiet = false;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("--scene", o->s.scenePath, "Scene JSON (default: scenes/paper-fig7.json)");
  cmd->add_option("--out", o->s.outDir, "Output folder")->required();
  cmd->add_option("--views", o->s.capture.views, "Number of views")->capture_default_str();
  cmd->add_option("--width", o->s.capture.width, "Image width, pixels")->capture_default_str();
  cmd->add_option("--height", o->s.capture.height, "Image height, pixels")->capture_default_str();
  cmd->add_option("--hfov-deg", o->s.capture.hfovDeg, "Horizontal field of view, degrees")->capture_default_str();
  cmd->add_option("--elevation-deg", o->s.elevationDeg, "Elevation range above the display plane, min,max degrees")
      ->capture_default_str();
  cmd->add_option("--spp", o->s.capture.spp, "Samples per pixel")->capture_default_str();
  cmd->add_option("--target", o->s.target,
                  "What the views frame: x0,y0,z0,x1,y1,z1 in mm (default: the scene's bounds within the display's "
                  "lenslet area in x, y and within +-VCP in z, i.e. what the display can show)");
  cmd->add_option("--display", o->s.displayPath, "Display whose area frames the default target (default: the paper's)");
  cmd->add_option("--radius-mm", o->radius, "Camera distance from the target centre (default: framing the target)");
  cmd->add_flag("--quiet", o->quiet, "Print nothing but warnings");
  addRunOptions(cmd, o->run, [o] {
    CaptureRunSettings s = o->s;
    o->run.applySeed(s.capture.seed);
    s.capture.progress = !o->quiet;
    if (o->radius > 0) s.capture.radiusMm = o->radius;
    const CaptureRunResult run = runCapture(s);
    const CaptureResult& r = run.capture;
    if (!o->quiet)
      std::printf("captured %s: %zu views of %d x %d px around (%.4g, %.4g, %.4g) mm at %.4g mm, %d spp, %.1f s\n"
                  "wrote:    %s\n",
                  run.scenePath.c_str(), r.views.size(), r.intrinsics.width, r.intrinsics.height, r.target.center().x,
                  r.target.center().y, r.target.center().z, r.radiusMm, s.capture.spp, r.seconds,
                  r.transformsPath.c_str());
  });
}

}  // namespace inim::cli
