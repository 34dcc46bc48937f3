// The Lego benchmark (long: minutes), run only with INIM_LEGO_BENCH=1: 200x200 views,
// every 8th image held out, trained on the rest; prints held-out PSNR, training time and
// rendering speed. Optional: INIM_LEGO_DIR (default /work/shared/data/lego),
// INIM_LEGO_ITERS, INIM_LEGO_SAVE (path of the trained model).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "lego_loader.h"
#include "radiance/grid_io.h"
#include "radiance/radiance_field.h"
#include "radiance/volume_renderer.h"

using namespace inim;

namespace {
// Process CPU time: the machine is shared, so wall time alone overstates the cost.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
double loadAverage() {
  double l[1] = {0.0};
  return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}
const char* env(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}
}  // namespace

TEST(LegoBench, HeldOutPsnr) {
  if (std::string(env("INIM_LEGO_BENCH", "0")) != "1") GTEST_SKIP() << "set INIM_LEGO_BENCH=1";
  std::string dir = env("INIM_LEGO_DIR", "/work/shared/data/lego");
  if (!std::filesystem::exists(dir + "/transforms_train.json")) GTEST_SKIP() << "no data in " << dir;
  auto t0 = std::chrono::steady_clock::now();
  std::vector<lego::View> views = lego::loadScene(dir, 4);
  TrainingRays trainRays;
  std::vector<size_t> test;
  for (size_t i = 0; i < views.size(); ++i) {
    if (i % 8 == 0)
      test.push_back(i);
    else
      lego::appendRays(views[i], trainRays);
  }
  double loadSec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("loaded %zu views (%zu train rays, %zu held out) in %.1f s\n", views.size(),
              trainRays.size(), test.size(), loadSec);

  TrainConfig cfg;
  cfg.iterations = std::atoi(env("INIM_LEGO_ITERS", "3000"));
  cfg.timeBudgetSeconds = std::atof(env("INIM_LEGO_BUDGET", "590"));
  cfg.progressInterval = 100;
  if (const char* tv = std::getenv("INIM_LEGO_TV")) cfg.tvDensity = std::atof(tv), cfg.tvColor = 0.1f * cfg.tvDensity;
  if (const char* b = std::getenv("INIM_LEGO_BATCH")) cfg.batchSize = std::atoi(b);
  if (const char* sh = std::getenv("INIM_LEGO_SH")) cfg.shDegree = std::atoi(sh);
  if (const char* st = std::getenv("INIM_LEGO_STAGES")) {  // "64:0,128:500,160:1500"
    cfg.resolutions.clear();
    cfg.stageStarts.clear();
    std::string s = st;
    for (size_t p = 0; p < s.size();) {
      size_t e = s.find(',', p);
      if (e == std::string::npos) e = s.size();
      std::string item = s.substr(p, e - p);
      size_t c = item.find(':');
      cfg.resolutions.push_back(std::atoi(item.substr(0, c).c_str()));
      cfg.stageStarts.push_back(std::atoi(item.substr(c + 1).c_str()));
      p = e + 1;
    }
  }
  VoxelGrid grid;
  double cpu0 = cpuSeconds();
  std::printf("load average before training: %.2f\n", loadAverage());
  TrainStats stats;
  if (const char* model = std::getenv("INIM_LEGO_MODEL"))  // evaluate a saved model only
    grid = loadVoxelGrid(model);
  else stats = train(grid, trainRays, cfg, [](const TrainProgress& p) {
    std::printf("it %5d/%d  loss %.5f  psnr %.2f  %.1f s (cpu %.1f s)  res %dx%dx%d  occ %.3f  spr %.1f\n",
                p.iteration, p.iterations, p.loss, p.psnr, p.elapsedSeconds, cpuSeconds(), p.res.x,
                p.res.y, p.res.z, p.occupiedFraction, p.samplesPerRay);
    std::fflush(stdout);
    return true;
  });
  std::printf("training cpu time %.1f s (%.2f cores busy on average), load average now %.2f\n",
              cpuSeconds() - cpu0, (cpuSeconds() - cpu0) / stats.seconds, loadAverage());
  std::printf("config: batch %d, sh %d, tv %g/%g, lr %g/%g\n", cfg.batchSize, cfg.shDegree,
              cfg.tvDensity, cfg.tvColor, cfg.lrDensity, cfg.lrColor);
  std::printf("trained %d iterations in %.1f s (grid %dx%dx%d, box [%.3f %.3f %.3f]-[%.3f %.3f %.3f])\n",
              stats.iterations, stats.seconds, grid.res.x, grid.res.y, grid.res.z, grid.lo.x,
              grid.lo.y, grid.lo.z, grid.hi.x, grid.hi.y, grid.hi.z);
  if (const char* save = std::getenv("INIM_LEGO_SAVE")) saveVoxelGrid(grid, save);

  VolumeRenderer renderer(grid);
  double sumPsnr = 0.0, sumMse = 0.0, renderSec = 0.0, renderCpu = 0.0;
  size_t rendered = 0;
  for (size_t i : test) {
    const lego::View& v = views[i];
    std::vector<RenderRay> rays(v.rgb.size());
    for (size_t k = 0; k < rays.size(); ++k) rays[k] = RenderRay{v.origin[k], v.dir[k]};
    std::vector<RadianceSample> out(rays.size());
    auto r0 = std::chrono::steady_clock::now();
    double c0 = cpuSeconds();
    renderer.render(rays, out);
    renderSec += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
    renderCpu += cpuSeconds() - c0;
    rendered += rays.size();
    std::vector<Vec3> rgb(out.size());
    for (size_t k = 0; k < out.size(); ++k) rgb[k] = out[k].rgb;
    double p = psnr(rgb, v.rgb);
    sumPsnr += p;
    sumMse += std::pow(10.0, -p / 10.0);
    std::printf("view %3zu  psnr %.2f\n", i, p);
  }
  double meanPsnr = sumPsnr / double(test.size());
  std::printf("held-out PSNR: mean %.2f dB (of mean MSE %.2f dB), train %.1f s, render %.0f rays/s "
              "wall, %.0f rays per cpu-second\n",
              meanPsnr, psnrFromMse(sumMse / double(test.size())), stats.seconds,
              double(rendered) / renderSec, double(rendered) / renderCpu);
  EXPECT_GE(meanPsnr, 28.0);
}
