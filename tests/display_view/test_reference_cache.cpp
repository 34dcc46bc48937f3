// The reference cache (display_view/reference_cache.h): a second render of the same inputs is
// read back bit for bit with the same ray counts; any input that changes the image changes the
// key; a damaged entry is rendered again; INIM_REFERENCE_CACHE=0 turns the cache off; a
// scene's key follows the files it names; an entry is verified by its hash on read; concurrent
// runs wait for a claimed entry instead of rendering it twice.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <thread>

#include <unistd.h>

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

// A readable image that is not the entry's (another entry's, copied over it) fails the stored
// SHA-256 and is rendered again; a folder given to the run is used even with the default cache off.
TEST(ReferenceCache, AnEntryIsVerifiedOnReadAndARunMayNameItsFolder) {
  ScratchDir scratch("reference_cache_verified");
  EnvVar off("INIM_REFERENCE_CACHE", "0");
  auto cam = pinholeCamera(ViewingPose{}, 12, 8, 0.01, 10.0);
  const SkyField sky;
  ReferenceSettings a = settings("sky"), b = settings("sky");
  a.cacheDir = b.cacheDir = (scratch.dir() / "references").string();
  b.seed = 2;
  const ViewResult first = renderReference(sky, Transform(), *cam, defaultCamera().sensor, a);
  const ViewResult other = renderReference(sky, Transform(), *cam, defaultCamera().sensor, b);
  ASSERT_EQ(entries(scratch.dir()), 2u);
  ASSERT_NE(first.image.data, other.image.data);
  const std::string keyA = referenceCacheKey("sky", Transform(), *cam, defaultCamera().sensor, a);
  const std::string keyB = referenceCacheKey("sky", Transform(), *cam, defaultCamera().sensor, b);
  const auto dir = scratch.dir() / "references";
  std::filesystem::copy_file(dir / (keyB + ".exr"), dir / (keyA + ".exr"),
                             std::filesystem::copy_options::overwrite_existing);
  const ViewResult again = renderReference(sky, Transform(), *cam, defaultCamera().sensor, a);
  EXPECT_FALSE(again.cached);
  EXPECT_EQ(again.image.data, first.image.data);
  EXPECT_TRUE(renderReference(sky, Transform(), *cam, defaultCamera().sensor, a).cached);
}

// A run that finds another live run's claim waits for its entry and reads it instead of
// rendering it too; a claim whose process is gone is taken over.
TEST(ReferenceCache, ConcurrentRunsWaitForTheClaimedEntry) {
  ScratchDir scratch("reference_cache_claim");
  auto cam = pinholeCamera(ViewingPose{}, 12, 8, 0.01, 10.0);
  const SkyField sky;
  ReferenceSettings s = settings("sky");
  s.cacheDir = (scratch.dir() / "references").string();
  const std::string key = referenceCacheKey("sky", Transform(), *cam, defaultCamera().sensor, s);
  ReferenceClaim held;
  ASSERT_FALSE(loadOrClaimReference(s.cacheDir, key, held));
  ASSERT_TRUE(held.held());
  ViewResult waited;
  std::thread other([&] { waited = renderReference(sky, Transform(), *cam, defaultCamera().sensor, s); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  // The holder renders (without the cache) and stores the entry, then lets the claim go.
  ReferenceSettings plain = s;
  plain.fieldKey = "";
  const ViewResult rendered = renderReference(sky, Transform(), *cam, defaultCamera().sensor, plain);
  storeCachedReference(s.cacheDir, key, rendered);
  held = ReferenceClaim();
  other.join();
  EXPECT_TRUE(waited.cached);
  EXPECT_EQ(waited.image.data, rendered.image.data);
  EXPECT_FALSE(std::filesystem::exists(s.cacheDir + "/" + key + ".lock"));

  // A claim left by a process that is gone: taken over at once.
  ReferenceSettings b = s;
  b.seed = 7;
  const std::string keyB = referenceCacheKey("sky", Transform(), *cam, defaultCamera().sensor, b);
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  std::ofstream(s.cacheDir + "/" + keyB + ".lock") << host << " 999999999\n";
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(renderReference(sky, Transform(), *cam, defaultCamera().sensor, b).cached);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  EXPECT_FALSE(std::filesystem::exists(s.cacheDir + "/" + keyB + ".lock"));
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
