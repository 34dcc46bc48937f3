// The reference cache (display_view/reference_cache.h): a second render of the same inputs is
// read back bit for bit with the same ray counts; any input that changes the image changes the
// key; a damaged entry is rendered again; INIM_REFERENCE_CACHE=0 turns the cache off; a
// scene's key follows the files it names.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>

#include "core/rng.h"
#include "display_view/reference_cache.h"
#include "scratch_dir.h"
#include "spectral/cie.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

// D65 at luminance 1 along every ray, scaled by `scale`.
class SkyField final : public Field {
 public:
  explicit SkyField(float scale = 1.0f) : scale_(scale) {}
  FieldEncoding encoding() const override { return FieldEncoding::Spectral; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda, std::span<FieldSample> out,
             uint64_t seed) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      out[i] = FieldSample{};
      // A little per-ray noise, so that seeds and sample counts show in the image.
      Rng rng = Rng::forSample(seed, rays[i].id, rays[i].sample);
      for (int k = 0; k < kNumWavelengths; ++k) out[i].L[k] = scale_ * float(cie::D65()(lambda[i][k])) * (0.9f + 0.2f * rng.uniform()) / 100.0f;
    }
  }
  void bounds(Point3& lo, Point3& hi) const override { lo = hi = Point3(0.0f); }

 private:
  float scale_;
};

// An environment variable set for the test's life.
class EnvVar {
 public:
  EnvVar(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~EnvVar() {
    if (old_) setenv(name_, old_->c_str(), 1);
    else unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// The cache on, in `dir` (ctest turns it off for every other test).
struct CacheDir {
  explicit CacheDir(const std::string& dir) : on("INIM_REFERENCE_CACHE", "1"), where("INIM_CACHE_DIR", dir) {}
  EnvVar on, where;
};

ReferenceSettings settings(const std::string& fieldKey) {
  ReferenceSettings s;
  s.spp = 4;
  s.progress = false;
  s.fieldKey = fieldKey;
  return s;
}

size_t entries(const std::filesystem::path& dir) {
  size_t n = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir / "references", ec))
    n += e.path().extension() == ".exr";
  return n;
}

}  // namespace

TEST(ReferenceCache, TheSecondRenderIsReadBackBitForBit) {
  ScratchDir scratch("reference_cache_hit");
  CacheDir cache(scratch.dir().string());
  auto cam = pinholeCamera(ViewingPose{}, 12, 8, 0.01, 10.0);
  const SkyField sky;
  const ViewResult first = renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings("sky"));
  const ViewResult second = renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings("sky"));
  EXPECT_FALSE(first.cached);
  EXPECT_TRUE(second.cached);
  EXPECT_EQ(entries(scratch.dir()), 1u);
  EXPECT_EQ(first.image.data, second.image.data);
  EXPECT_EQ(first.image.channels, second.image.channels);
  EXPECT_EQ(first.stats.tracedRays, second.stats.tracedRays);
  EXPECT_EQ(first.stats.emittingRays, second.stats.emittingRays);
  // No key: never cached.
  const ViewResult uncached = renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings(""));
  EXPECT_FALSE(uncached.cached);
  EXPECT_EQ(uncached.image.data, first.image.data);
  EXPECT_EQ(entries(scratch.dir()), 1u);
}

TEST(ReferenceCache, EveryInputTheImageDependsOnChangesTheKey) {
  auto cam = pinholeCamera(ViewingPose{}, 12, 8, 0.01, 10.0);
  auto wider = pinholeCamera(ViewingPose{}, 14, 8, 0.01, 10.0);
  auto longer = pinholeCamera(ViewingPose{}, 12, 8, 0.01, 11.0);
  const CameraSensor& sensor = defaultCamera().sensor;
  const ReferenceSettings s = settings("sky");
  const std::string key = referenceCacheKey("sky", Transform(), *cam, sensor, s);
  EXPECT_EQ(key, referenceCacheKey("sky", Transform(), *cam, sensor, s));
  EXPECT_EQ(key.size(), 64u);
  std::vector<std::string> others = {referenceCacheKey("sea", Transform(), *cam, sensor, s),
                                     referenceCacheKey("sky", Transform::translate(Vec3d(0, 0, 1)), *cam, sensor, s),
                                     referenceCacheKey("sky", Transform(), *wider, sensor, s),
                                     referenceCacheKey("sky", Transform(), *longer, sensor, s)};
  for (auto change : std::vector<std::function<void(ReferenceSettings&)>>{
           [](ReferenceSettings& r) { r.spp = 5; }, [](ReferenceSettings& r) { r.seed = 2; },
           [](ReferenceSettings& r) { r.depth = true; },
           [](ReferenceSettings& r) { r.dispersion = CameraDispersion::Trace; }}) {
    ReferenceSettings r = s;
    change(r);
    others.push_back(referenceCacheKey("sky", Transform(), *cam, sensor, r));
  }
  std::vector<uint8_t> mask(12 * 8, 1);
  ReferenceSettings masked = s;
  masked.fullSamples = &mask;
  others.push_back(referenceCacheKey("sky", Transform(), *cam, sensor, masked));
  mask[5] = 0;
  others.push_back(referenceCacheKey("sky", Transform(), *cam, sensor, masked));
  for (size_t i = 0; i < others.size(); ++i) {
    EXPECT_NE(others[i], key) << "change " << i;
    for (size_t j = 0; j < i; ++j) EXPECT_NE(others[i], others[j]) << "changes " << i << " and " << j;
  }
}

TEST(ReferenceCache, ADamagedEntryIsRenderedAgainAndTheCacheTurnsOff) {
  ScratchDir scratch("reference_cache_damaged");
  auto cam = pinholeCamera(ViewingPose{}, 12, 8, 0.01, 10.0);
  const SkyField sky;
  ViewResult first;
  {
    CacheDir cache(scratch.dir().string());
    first = renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings("sky"));
    ASSERT_EQ(entries(scratch.dir()), 1u);
    for (const auto& e : std::filesystem::directory_iterator(scratch.dir() / "references"))
      if (e.path().extension() == ".exr") std::filesystem::resize_file(e.path(), 100);
    const ViewResult again = renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings("sky"));
    EXPECT_FALSE(again.cached);
    EXPECT_EQ(again.image.data, first.image.data);
    EXPECT_TRUE(renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings("sky")).cached);
  }
  EnvVar off("INIM_REFERENCE_CACHE", "0");
  EXPECT_EQ(referenceCacheDir(), "");
  EXPECT_FALSE(renderReference(sky, Transform(), *cam, defaultCamera().sensor, settings("sky")).cached);
}

TEST(ReferenceCache, ASceneKeyFollowsTheFilesItNames) {
  ScratchDir scratch("reference_cache_scene");
  std::filesystem::create_directories(scratch.dir());
  const auto scene = (scratch.dir() / "scene.json").string(), mesh = (scratch.dir() / "mesh.obj").string();
  std::ofstream(scene) << R"({"objects": [{"type": "mesh", "file": "mesh.obj"}], "name": "not a file", "_note": ")"
                        << std::string(300, 'x') << R"("})";
  std::ofstream(mesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string before = fieldContentKey(scene);
  EXPECT_EQ(before, fieldContentKey(scene));
  std::ofstream(mesh) << "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string after = fieldContentKey(scene);
  EXPECT_NE(before, after);
  std::ofstream(scene) << R"({"objects": [{"type": "mesh", "file": "mesh.obj"}], "name": "not a file "})";
  EXPECT_NE(fieldContentKey(scene), after);
}
