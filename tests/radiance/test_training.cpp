// Training on an analytic scene: held-out PSNR, and determinism across thread counts.
// INIM_SYN_ITERS / INIM_SYN_PI override the iteration count and progress interval.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "core/parallel.h"
#include "radiance/volume_renderer.h"
#include "synthetic_scene.h"

using namespace inim;

TEST(Training, SyntheticSpheresHeldOutPsnr) {
  const int views = 24, size = 64;
  TrainingRays trainRays, testRays;
  for (int v = 0; v < views; ++v) synthetic::render(v, views, size, v % 6 == 3 ? testRays : trainRays);
  TrainConfig cfg = synthetic::config();
  if (const char* it = std::getenv("INIM_SYN_ITERS")) cfg.iterations = std::atoi(it);
  if (const char* pi = std::getenv("INIM_SYN_PI")) cfg.progressInterval = std::atoi(pi);
  VoxelGrid grid;
  auto t0 = std::chrono::steady_clock::now();
  TrainStats stats = train(grid, trainRays, cfg, [](const TrainProgress& p) {
    std::printf("it %4d  batch psnr %.2f  %.1f s  res %dx%dx%d  occ %.3f\n", p.iteration, p.psnr,
                p.elapsedSeconds, p.res.x, p.res.y, p.res.z, p.occupiedFraction);
    std::fflush(stdout);
    return true;
  });
  double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(stats.iterations, cfg.iterations);
  VolumeRenderer renderer(grid);
  std::vector<RenderRay> rays(testRays.size());
  for (size_t i = 0; i < rays.size(); ++i) rays[i] = RenderRay{testRays.origin[i], testRays.dir[i]};
  std::vector<RadianceSample> out(rays.size());
  renderer.render(rays, out);
  std::vector<Vec3> rgb(out.size());
  for (size_t i = 0; i < out.size(); ++i) rgb[i] = out[i].rgb;
  double p = psnr(rgb, testRays.rgb);
  std::printf("synthetic: held-out PSNR %.2f dB after %.1f s of training (grid %dx%dx%d)\n", p, sec,
              grid.res.x, grid.res.y, grid.res.z);
  EXPECT_GT(p, 30.0);
}

TEST(Training, BitIdenticalForAnyThreadCount) {
  TrainingRays rays;
  for (int v = 0; v < 6; ++v) synthetic::render(v, 6, 32, rays);
  TrainConfig cfg = synthetic::config();
  cfg.iterations = 40;
  cfg.batchSize = 1024;
  cfg.resolutions = {24, 40};
  cfg.stageStarts = {0, 20};  // crosses a stage change (box tightening, resampling)
  cfg.shDegree = 1;
  cfg.tvDensity = 1e-4f;
  cfg.tvColor = 1e-5f;
  VoxelGrid one, two;
  {
    ThreadLimit limit(1);
    train(one, rays, cfg);
  }
  {
    ThreadLimit limit(2);
    train(two, rays, cfg);
  }
  EXPECT_EQ(one.res, two.res);
  EXPECT_EQ(one.lo, two.lo);
  ASSERT_EQ(one.density.size(), two.density.size());
  EXPECT_TRUE(one.density == two.density);
  EXPECT_TRUE(one.color == two.color);
  // And the training actually changed the grid.
  VoxelGrid fresh = VoxelGrid::create(one.lo, one.hi, one.res, 1, one.activation, one.background, cfg.initAlpha);
  EXPECT_FALSE(one.density == fresh.density);
}

TEST(Training, RejectsBadConfig) {
  TrainingRays rays;
  VoxelGrid g;
  EXPECT_THROW(train(g, rays, TrainConfig{}), InputError);
  synthetic::render(0, 1, 8, rays);
  TrainConfig cfg = synthetic::config();
  cfg.shDegree = 3;
  EXPECT_THROW(train(g, rays, cfg), InputError);
  cfg = synthetic::config();
  cfg.stageStarts = {0};
  EXPECT_THROW(train(g, rays, cfg), InputError);
  cfg = synthetic::config();
  cfg.boxHi.x = -2.0f;
  EXPECT_THROW(train(g, rays, cfg), InputError);
  rays.rgb.pop_back();
  EXPECT_THROW(train(g, rays, synthetic::config()), InputError);
}

// A grid of 1024 vertices a side is about 480 GiB while training (parameters, gradients and
// Adam's moments): refused at the memory limit, naming the stage's resolution, before anything
// is allocated.
TEST(Training, AGridBeyondTheMemoryLimitIsRefusedBeforeAllocating) {
  TrainingRays rays;
  synthetic::render(0, 1, 8, rays);
  TrainConfig cfg = synthetic::config();
  cfg.shDegree = 2;
  cfg.resolutions = {64, 1024};
  cfg.stageStarts = {0, 10};
  VoxelGrid g;
  try {
    train(g, rays, cfg);
    FAIL() << "a 1024^3 training grid accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "resolutions");
    EXPECT_EQ(e.value().rfind("1024 (", 0), 0u) << e.value();
    EXPECT_NE(e.expected().find("memory limit"), std::string::npos) << e.expected();
  }
  EXPECT_TRUE(g.density.empty() && g.color.empty());  // nothing trained, nothing allocated
}
