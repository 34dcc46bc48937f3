// sweep/: the cost of one design point of a sweep (EIA, five views, five references and the
// budget at 648 px on the default design), run as `inim sweep` runs it (runSweepPoint), twice in
// one folder: the first point renders its references into the sweep's cache, the second (another
// gap, so another display) reads them back. Their wall times give the points per hour of a
// 2-core machine before and after the references' reuse.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

#include "bench/bench_context.h"
#include "core/format.h"
#include "sweep/sweep_point.h"
#include "sweep/sweep_run.h"

namespace inim::bench {

namespace {

struct PointTimes {
  double cold = 0, warm = 0;
  int cachedCold = 0, cachedWarm = 0;
};
PointTimes& pointTimes() {
  static PointTimes t;
  return t;
}

void benchSweepPoint(benchmark::State& state) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("inim_bench_sweep_" + std::to_string(getpid()));
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  const SweepPlan plan = sweepPlanFromJson(
      parseJsonText(R"({"base": {"fig11": {"budget": true}},
                        "axes": [{"path": "reconstruction_gap_mm", "values": [4.0, 4.2]}]})", "bench plan"),
      "bench plan");
  const std::vector<SweepPoint> points = prepareSweep(plan, dir.string(), "inim", 2);
  PointTimes& t = pointTimes();
  for (auto _ : state) {
    for (int i = 0; i < 2; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const Json r = runSweepPoint(dir.string(), points[i].id, 0, sweepReferenceCache(dir.string()));
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (r.value("status", "") != "ok") state.SkipWithError(r.value("error", "point failed").c_str());
      (i == 0 ? t.cold : t.warm) = s;
      (i == 0 ? t.cachedCold : t.cachedWarm) = r.contains("references") ? r["references"].value("cached", 0) : 0;
    }
  }
  state.counters["point_s_cold"] = t.cold;
  state.counters["point_s_cached_refs"] = t.warm;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace

void registerSweepBenchmarks() {
  benchmark::RegisterBenchmark("sweep/point-648px-budget", benchSweepPoint)
      ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
}

void printSweepBenchResults() {
  const PointTimes& t = pointTimes();
  if (t.cold <= 0 || t.warm <= 0) return;
  std::printf("\nsweep point (EIA + 5 views + 5 references + budget, 648 px), same run: %.1f s rendering its "
              "references (%d cached), %.1f s reading them from the sweep's cache (%d cached); %.0f -> %.0f points "
              "per hour, x%.2f\n",
              t.cold, t.cachedCold, t.warm, t.cachedWarm, 3600 / t.cold, 3600 / t.warm, t.cold / t.warm);
}

}  // namespace inim::bench
