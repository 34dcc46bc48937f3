// inim capture: a posed synthetic dataset of an analytic scene (transforms.json + PNGs), like
// the smartphone scan of the paper's workflow, so scene -> capture -> train -> EIA -> view
// runs in software against exact ground truth. See src/runs/capture_run.h.
#include <cstdio>
#include <memory>

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
  addSetting(cmd, "scene", o->s.scenePath);
  addSetting(cmd, "out", o->s.outDir)->required();
  addSetting(cmd, "views", o->s.capture.views);
  addSetting(cmd, "width", o->s.capture.width);
  addSetting(cmd, "height", o->s.capture.height);
  addSetting(cmd, "hfov_deg", o->s.capture.hfovDeg);
  addSetting(cmd, "elevation_deg", o->s.elevationDeg);
  addSetting(cmd, "spp", o->s.capture.spp);
  addSetting(cmd, "target", o->s.target);
  addSetting(cmd, "display", o->s.displayPath);
  addSetting(cmd, "radius_mm", o->radius);
  addSetting(cmd, "quiet", o->quiet);
  addRunOptions(cmd, o->run, [o] {
    CaptureRunSettings s = o->s;
    o->run.applySeed(s.capture.seed);
    s.capture.progress = !o->quiet;
    if (o->radius > 0) s.capture.radiusMm = o->radius;
    const CaptureRunResult run = runCapture(s);
    if (!o->quiet) std::printf("%s", captureText(s, run).c_str());
  });
}

}  // namespace inim::cli
