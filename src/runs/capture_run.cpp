#include "runs/capture_run.h"

#include <algorithm>
#include <cstdio>

#include "core/format.h"
#include "core/error.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "field_files/field_factory.h"
#include "scene/analytic_scene.h"
#include "synthesis/eia_synthesis.h"

namespace inim {

Box3d captureTargetForDisplay(const Field& scene, const std::string& scenePath, const std::string& displayPath) {
  const Display d = loadDisplay(displayPathOrDefault(displayPath));
  const EiLayout L = computeLayout(d);
  const auto a = L.activeArea();
  Point3 lo, hi;
  scene.bounds(lo, hi);
  Box3d t{{std::max<double>(lo.x, a.x0), std::max<double>(lo.y, a.y0), std::max<double>(lo.z, -kDefaultVcpMm)},
          {std::min<double>(hi.x, a.x1), std::min<double>(hi.y, a.y1), std::min<double>(hi.z, kDefaultVcpMm)}};
  if (!(t.lo.x < t.hi.x && t.lo.y < t.hi.y && t.lo.z < t.hi.z))
    throw InputError(scenePath, "bounds", "outside the display's area", "a scene in front of the display, or --target");
  return t;
}

CaptureRunResult runCapture(const CaptureRunSettings& s) {
  CaptureSettings cs = s.capture;
  double e0 = 0, e1 = 0;
  if (std::sscanf(s.elevationDeg.c_str(), "%lf,%lf", &e0, &e1) != 2)
    throw InputError("", "elevation_deg", "\"" + s.elevationDeg + "\"", "min,max in degrees");
  cs.minElevationDeg = e0, cs.maxElevationDeg = e1;
  CaptureRunResult r;
  r.scenePath = s.scenePath.empty() ? defaultScenePath() : s.scenePath;
  auto scene = AnalyticScene::load(r.scenePath);
  cs.sceneFile = r.scenePath;
  if (!s.target.empty()) {
    double v[6];
    if (std::sscanf(s.target.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) != 6 ||
        !(v[0] < v[3] && v[1] < v[4] && v[2] < v[5]))
      throw InputError("", "target", "\"" + s.target + "\"", "x0,y0,z0,x1,y1,z1 with x0 < x1, y0 < y1, z0 < z1");
    cs.target = Box3d{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  } else {
    cs.target = captureTargetForDisplay(*scene, r.scenePath, s.displayPath);
  }
  r.capture = captureScene(*scene, cs, s.outDir);
  return r;
}

std::string captureText(const CaptureRunSettings& s, const CaptureRunResult& run) {
  const CaptureResult& r = run.capture;
  const Vec3d c = r.target.center();
  return formatText("captured %s: %zu views of %d x %d px around (%.4g, %.4g, %.4g) mm at %.4g mm, %d spp, %.1f s\n"
                    "wrote:    %s\n",
                    run.scenePath.c_str(), r.views.size(), r.intrinsics.width, r.intrinsics.height, c.x, c.y, c.z,
                    r.radiusMm, s.capture.spp, r.seconds, r.transformsPath.c_str());
}

}  // namespace inim
