// Synthetic capture: camera placement, and a captured dataset that round-trips through the
// dataset loader with rays that hit the scene where the rendered depth says.
#include "capture/capture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "capture/capture_poses.h"
#include "core/output_file.h"
#include "expect_input_error.h"
#include "camera/fov_camera.h"
#include "scene/analytic_scene.h"
#include "scratch_dir.h"

using namespace inim;
namespace fs = std::filesystem;

namespace {

ScratchDir& scratch() {
  static ScratchDir s("capture");
  return s;
}

// A sphere in front of a plane, lit by a uniform environment: smooth depth almost everywhere,
// and the plane's edges leave some background (A = 0) at grazing views.
std::unique_ptr<AnalyticScene> smallScene() {
  Json j = Json::parse(R"({
    "materials": {"grey": {"type": "diffuse", "reflectance": [0.6, 0.5, 0.4]}},
    "objects": [
      {"id": 1, "type": "sphere", "radius_mm": 10, "translate_mm": [0, 0, 5], "material": "grey"},
      {"id": 2, "type": "rectangle", "size_mm": [60, 40], "translate_mm": [0, 0, -10], "material": "grey"}],
    "lights": [{"type": "environment", "spectrum": "D65", "scale": 1}]})");
  return AnalyticScene::fromJson(j, "small-scene.json");
}

// Checks that frameRay of the loaded frames hits `scene` at the rendered depth, on pixels whose
// depth is smooth (the render's depth is a mean over the pixel area). Returns pixels checked.
int checkDepths(const AnalyticScene& scene, const Dataset& ds, const CaptureResult& cap) {
  int checked = 0;
  for (size_t v = 0; v < ds.frames.size(); ++v) {
    const Image& Z = cap.views[v].depth;
    for (int y = 1; y + 1 < Z.height; y += 3)
      for (int x = 1; x + 1 < Z.width; x += 3) {
        float z = Z.at(x, y, 0), lo = z, hi = z;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            lo = std::min(lo, Z.at(x + dx, y + dy, 0));
            hi = std::max(hi, Z.at(x + dx, y + dy, 0));
          }
        if (!(lo > 0) || hi - lo > 0.01f * z) continue;  // a silhouette or an edge nearby
        glm::dvec3 o, d;
        frameRay(ds.frames[v], x + 0.5, y + 0.5, o, d);
        Ray ray;
        ray.o = Point3(o);
        ray.d = Vec3(d);
        Hit hit;
        EXPECT_TRUE(scene.intersect(ray, hit)) << "view " << v << " pixel " << x << "," << y;
        EXPECT_NEAR(hit.t, z, 0.003f * z + 0.05f) << "view " << v << " pixel " << x << "," << y;
        ++checked;
      }
  }
  return checked;
}

}  // namespace

TEST(CapturePoses, CapDirectionsCoverTheFrontCap) {
  auto dirs = capDirections(64, 50, 90);
  ASSERT_EQ(dirs.size(), 64u);
  glm::dvec3 mean(0.0);
  for (const auto& d : dirs) {
    EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
    double el = std::asin(d.z) * 180 / M_PI;
    EXPECT_GE(el, 50.0);
    EXPECT_LE(el, 90.0);
    mean += d;
  }
  mean /= 64.0;
  // Evenly spread: the mean direction is (close to) the cap's axis.
  EXPECT_LT(std::hypot(mean.x, mean.y), 0.02);
  // Deterministic.
  EXPECT_EQ(capDirections(64, 50, 90)[17], dirs[17]);
}

TEST(CapturePoses, PoseMatchesTheRenderCamera) {
  FovCameraSettings cs;
  cs.width = 40;
  cs.height = 30;
  cs.hfovDeg = 40;
  cs.pose.eye = Point3d(30, 70, 150);
  cs.pose.lookAt = Point3d(1, -2, -5);
  FovCameraModel cam(cs);
  DatasetFrame f;
  f.cameraToWorld = lookAtCameraToWorld(cs.pose.eye, cs.pose.lookAt);
  f.intrinsics.width = 40;
  f.intrinsics.height = 30;
  f.intrinsics.fx = f.intrinsics.fy = 20 / std::tan(20 * M_PI / 180);
  f.intrinsics.cx = 20;
  f.intrinsics.cy = 15;
  for (float px : {0.5f, 13.25f, 39.5f})
    for (float py : {0.5f, 21.0f, 29.5f}) {
      Ray r;
      cam.generateRay(Vec2(px, py), Vec2(0.5f), 550.0f, r);
      glm::dvec3 o, d;
      frameRay(f, px, py, o, d);
      EXPECT_NEAR(glm::length(glm::dvec3(r.o) - o), 0.0, 1e-4);
      EXPECT_NEAR(glm::length(glm::dvec3(r.d) - d), 0.0, 1e-6);
    }
}

TEST(Capture, RoundTripsThroughTheLoader) {
  auto scene = smallScene();
  CaptureSettings s;
  s.views = 6;
  s.width = 48;
  s.height = 36;
  s.spp = 4;
  s.keepDepth = true;
  s.sceneFile = "small-scene.json";
  s.progress = false;
  std::string out = scratch().path("roundtrip");
  CaptureResult cap = captureScene(*scene, s, out);
  ASSERT_EQ(cap.views.size(), 6u);
  EXPECT_TRUE(fs::exists(out + "/images/frame_0006.png"));
  EXPECT_EQ(cap.transformsPath, out + "/transforms.json");
  // Default framing: the 60 x 40 mm target's x extent at the front of the box.
  Point3 lo, hi;
  scene->bounds(lo, hi);
  EXPECT_NEAR(cap.radiusMm, 0.5 * (hi.z - lo.z) + 30 / std::tan(20 * M_PI / 180), 1e-3);
  // Every camera is in front of the scene (z > 0 side) and looks toward -z.
  for (const auto& v : cap.views) {
    EXPECT_GT(v.cameraToWorld[3].z, 0.0);
    EXPECT_GT(v.cameraToWorld[2].z, 0.6);  // camera +z (backward) within 50 deg of world +z
  }

  nlohmann::json j = nlohmann::json::parse(std::ifstream(cap.transformsPath));
  EXPECT_EQ(j["inim_capture"]["units"], "mm");
  EXPECT_EQ(j["inim_capture"]["scene"], "small-scene.json");
  EXPECT_EQ(j["frames"][0]["file_path"], "images/frame_0001.png");

  DatasetOptions o;
  o.background = glm::vec3(0.0f);  // the analytic scene's own background: alpha 0 -> black
  o.holdoutEvery = 0;
  Dataset ds = loadDataset(out, o);
  EXPECT_EQ(ds.format, "nerfstudio");
  ASSERT_EQ(ds.frames.size(), 6u);
  EXPECT_TRUE(ds.frames[0].hadAlpha);
  EXPECT_EQ(ds.frames[0].intrinsics.width, 48);
  EXPECT_NEAR(ds.frames[0].intrinsics.fx, cap.intrinsics.fx, 1e-9);
  for (size_t i = 0; i < 6; ++i)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(glm::length(ds.frames[i].cameraToWorld[c] - cap.views[i].cameraToWorld[c]), 0.0, 1e-9);
  EXPECT_GT(checkDepths(*scene, ds, cap), 60);
  // The scene box estimate of a capture centred on the target contains the target's centre.
  EXPECT_TRUE(ds.sceneBox.contains(cap.target.center()));
}

TEST(Capture, PaperSceneRoundTrip) {
  auto scene = AnalyticScene::load(dataPath("scenes/paper-fig7.json"));
  CaptureSettings s;
  s.views = 3;
  s.width = 64;
  s.height = 48;
  s.spp = 1;
  s.keepDepth = true;
  s.sceneFile = scene->file();
  s.progress = false;
  std::string out = scratch().path("paper");
  CaptureResult cap = captureScene(*scene, s, out);
  DatasetOptions o;
  o.background = glm::vec3(0.0f);
  Dataset ds = loadDataset(out + "/transforms.json", o);
  ASSERT_EQ(ds.frames.size(), 3u);
  EXPECT_GT(checkDepths(*scene, ds, cap), 50);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(cap.transformsPath));
  EXPECT_EQ(j["inim_capture"]["scene"], scene->file());
}

TEST(Capture, BadSettingsWriteNothing) {
  auto scene = smallScene();
  std::string out = scratch().path("bad");
  CaptureSettings s;
  s.progress = false;
  s.views = 0;
  EXPECT_EQ(expectInputError([&] { captureScene(*scene, s, out); }).key(), "views");
  s.views = 2;
  s.minElevationDeg = 80;
  s.maxElevationDeg = 40;
  EXPECT_EQ(expectInputError([&] { captureScene(*scene, s, out); }).key(), "elevation_deg");
  s.maxElevationDeg = 90;
  s.radiusMm = -5.0;
  EXPECT_EQ(expectInputError([&] { captureScene(*scene, s, out); }).key(), "radius_mm");
  EXPECT_FALSE(fs::exists(out + "/transforms.json"));
}

// The default capture of the default scene, for timing (run with --gtest_also_run_disabled_tests).
TEST(Capture, DISABLED_DefaultPaperScene) {
  auto scene = AnalyticScene::load(dataPath("scenes/paper-fig7.json"));
  CaptureSettings s;
  s.sceneFile = scene->file();
  std::string out = scratch().path("default");
  CaptureResult cap = captureScene(*scene, s, out);
  std::printf("default capture: %zu views %dx%d spp %d, radius %.1f mm, target (%.1f %.1f %.1f)-(%.1f %.1f %.1f), "
              "%.1f s, %.1f Mrays\n",
              cap.views.size(), s.width, s.height, s.spp, cap.radiusMm, cap.target.lo.x, cap.target.lo.y,
              cap.target.lo.z, cap.target.hi.x, cap.target.hi.y, cap.target.hi.z, cap.seconds,
              cap.raysTraced * 1e-6);
  Dataset ds = loadDataset(out);
  EXPECT_EQ(ds.frames.size(), 64u);
  if (const char* keep = std::getenv("INIM_KEEP_CAPTURE")) fs::copy(out, keep, fs::copy_options::recursive);
}
