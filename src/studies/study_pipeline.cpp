#include "studies/study_pipeline.h"

#include <cmath>

#include "synthesis/eia_synthesis.h"
#include "scene/analytic_scene.h"

namespace inim::study_detail {

Image synthesizeAt(const EiLayout& L, const Display& d, const Json& scene, double zMm, int spp) {
  auto field = AnalyticScene::fromJson(scene, "(study scene)");
  SynthesisSettings settings;
  settings.placement.translateMm = Vec3d(0.0, 0.0, zMm);
  settings.spp = spp;
  settings.autoExposure = false;  // exposure 1: every depth's EIA in the same units
  settings.progress = false;
  return synthesizeEia(L, d.panel, *field, settings).eia;
}

Json litRectangleScene(double wMm, double hMm, const Json& reflectance, double rotateZDeg) {
  Json obj = {{"id", 1}, {"name", "target"}, {"type", "rectangle"}, {"size_mm", {wMm, hMm}}, {"material", "target"}};
  if (rotateZDeg != 0.0) obj["rotate_deg"] = {0.0, 0.0, rotateZDeg};
  return Json{{"units", "mm"},
              {"integrator", {{"type", "direct"}}},
              {"materials", {{"target", {{"type", "diffuse"}, {"reflectance", reflectance}}}}},
              {"objects", Json::array({obj})},
              {"lights", Json::array({{{"name", "distant"},
                                       {"type", "point"},
                                       {"position_mm", {0, 0, 1000000}},
                                       {"spectrum", 1.0},
                                       {"scale", 3.14159265358979e12}}})}};
}

Json emissiveSphereScene(double radiusMm, double scale) {
  return Json{{"units", "mm"},
              {"materials", {{"glow", {{"type", "emitter"}, {"spectrum", "D65"}, {"scale", scale}}}}},
              {"objects", Json::array({{{"id", 1},
                                        {"name", "point"},
                                        {"type", "sphere"},
                                        {"radius_mm", radiusMm},
                                        {"material", "glow"}}})}};
}

std::unique_ptr<CameraModel> axialThinLens(double D, double focusZ, int W, int H, double sampleMm) {
  const double f = 12.0, N = 4.0, s = D - focusZ;
  const double sPrime = f * s / (s - f);
  SensorGeometry g;
  g.widthPx = W;
  g.heightPx = H;
  g.pitchMm = sampleMm * sPrime / s;
  ViewingPose pose;
  pose.eye = Point3d(0.0, 0.0, D);
  pose.lookAt = Point3d(0.0, 0.0, focusZ);
  pose.up = Vec3d(0.0, 1.0, 0.0);
  return std::make_unique<ThinLensCameraModel>(g, pose, f, N, s, false);
}

glm::dvec2 pixelOnPlane(const CameraModel& cam, int x, int y, double zMm) {
  Ray r;
  cam.generateRay(Vec2(float(x) + 0.5f, float(y) + 0.5f), Vec2(0.5f, 0.5f), 550.0f, r);
  const double t = (zMm - double(r.o.z)) / double(r.d.z);
  return {double(r.o.x) + t * double(r.d.x), double(r.o.y) + t * double(r.d.y)};
}

double lum(const Image& img, int x, int y) {
  return 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
}

}  // namespace inim::study_detail
