// inim capture: a posed synthetic dataset of an analytic scene (transforms.json + PNGs), like
// the smartphone scan of the paper's workflow, so scene -> capture -> train -> EIA -> view
// runs in software against exact ground truth. See src/capture/capture.h.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "capture/capture.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "fields/field_factory.h"
#include "scene/analytic_scene.h"
#include "synthesis/eia_synthesis.h"

namespace inim::cli {

void addCaptureCommand(CLI::App& app) {
  struct Opts {
    std::string scene, out, display, target, elevation = "50,90";
    CaptureSettings s;
    double radius = 0;
    bool quiet = false;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "capture", "Render a posed dataset of an analytic scene from a cap of camera positions in front of it "
                 "(transforms.json + sRGB PNGs with alpha), for inim train or any NeRF tool");
  cmd->add_option("--scene", o->scene, "Scene JSON (default: scenes/paper-fig7.json)");
  cmd->add_option("--out", o->out, "Output folder")->required();
  cmd->add_option("--views", o->s.views, "Number of views")->capture_default_str();
  cmd->add_option("--width", o->s.width, "Image width, pixels")->capture_default_str();
  cmd->add_option("--height", o->s.height, "Image height, pixels")->capture_default_str();
  cmd->add_option("--hfov-deg", o->s.hfovDeg, "Horizontal field of view, degrees")->capture_default_str();
  cmd->add_option("--elevation-deg", o->elevation, "Elevation range above the display plane, min,max degrees")
      ->capture_default_str();
  cmd->add_option("--spp", o->s.spp, "Samples per pixel")->capture_default_str();
  cmd->add_option("--target", o->target,
                  "What the views frame: x0,y0,z0,x1,y1,z1 in mm (default: the scene's bounds within the display's "
                  "lenslet area in x, y and within +-VCP in z, i.e. what the display can show)");
  cmd->add_option("--display", o->display, "Display whose area frames the default target (default: the paper's)");
  cmd->add_option("--radius-mm", o->radius, "Camera distance from the target centre (default: framing the target)");
  cmd->add_flag("--quiet", o->quiet, "Print nothing but warnings");
  addRunOptions(cmd, o->run, [o] {
    CaptureSettings s = o->s;
    s.seed = o->run.seed;
    s.progress = !o->quiet;
    double e0 = 0, e1 = 0;
    if (std::sscanf(o->elevation.c_str(), "%lf,%lf", &e0, &e1) != 2)
      throw InputError("", "--elevation-deg", "\"" + o->elevation + "\"", "min,max in degrees");
    s.minElevationDeg = e0, s.maxElevationDeg = e1;
    if (o->radius > 0) s.radiusMm = o->radius;
    const std::string scenePath = o->scene.empty() ? defaultScenePath() : o->scene;
    auto scene = AnalyticScene::load(scenePath);
    s.sceneFile = scenePath;
    if (!o->target.empty()) {
      double v[6];
      if (std::sscanf(o->target.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) != 6 ||
          !(v[0] < v[3] && v[1] < v[4] && v[2] < v[5]))
        throw InputError("", "--target", "\"" + o->target + "\"", "x0,y0,z0,x1,y1,z1 with x0 < x1, y0 < y1, z0 < z1");
      s.target = Box3d{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    } else {
      // A scene's backdrop can dwarf what the display shows: frame the part of the scene the
      // display can show (its lenslet area, and depths within the default VCP).
      Display d = loadDisplay(displayPathOrDefault(o->display));
      const EiLayout L = computeLayout(d);
      const auto a = L.activeArea();
      Point3 lo, hi;
      scene->bounds(lo, hi);
      Box3d t{{std::max<double>(lo.x, a.x0), std::max<double>(lo.y, a.y0), std::max<double>(lo.z, -kDefaultVcpMm)},
              {std::min<double>(hi.x, a.x1), std::min<double>(hi.y, a.y1), std::min<double>(hi.z, kDefaultVcpMm)}};
      if (!(t.lo.x < t.hi.x && t.lo.y < t.hi.y && t.lo.z < t.hi.z))
        throw InputError(scenePath, "bounds", "outside the display's area", "a scene in front of the display, or --target");
      s.target = t;
    }
    CaptureResult r = captureScene(*scene, s, o->out);
    if (!o->quiet)
      std::printf("captured %s: %zu views of %d x %d px around (%.4g, %.4g, %.4g) mm at %.4g mm, %d spp, %.1f s\n"
                  "wrote:    %s\n",
                  scenePath.c_str(), r.views.size(), r.intrinsics.width, r.intrinsics.height, r.target.center().x,
                  r.target.center().y, r.target.center().z, r.radiusMm, s.spp, r.seconds, r.transformsPath.c_str());
  });
}

}  // namespace inim::cli
