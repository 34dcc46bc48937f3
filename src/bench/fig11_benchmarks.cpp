// fig11/: `inim fig11` on its defaults (648 px, the default scene, display and camera), plain and
// with the error budget, each once, into a scratch folder: the budget's cost as a ratio of the
// two wall times measured in the same run (target: budget <= 3 x plain; plain <= 30 s).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <unistd.h>

#include "bench/bench_context.h"
#include "runs/fig11.h"

namespace inim::bench {

namespace {

std::map<std::string, double>& fig11Seconds() {
  static std::map<std::string, double> s;
  return s;
}

void benchFig11(benchmark::State& state, bool budget) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("inim_bench_fig11_" + std::to_string(getpid()));
  for (auto _ : state) {
    Fig11Settings s;
    s.outDir = dir.string();
    s.budget = budget;
    const auto t0 = std::chrono::steady_clock::now();
    const Fig11Result r = runFig11(s);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fig11Seconds()[budget ? "budget" : "plain"] = seconds;
    if (budget && !r.budgets.empty()) state.counters["noise_floor_de"] = r.budgets.front().noiseFloor.deltaE.mean;
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace

void registerFig11Benchmarks() {
  benchmark::RegisterBenchmark("fig11/plain-648px", [](benchmark::State& s) { benchFig11(s, false); })
      ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
  benchmark::RegisterBenchmark("fig11/budget-648px", [](benchmark::State& s) { benchFig11(s, true); })
      ->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
}

void printFig11BenchResults() {
  auto& s = fig11Seconds();
  if (!s.count("plain") || !s.count("budget")) return;
  std::printf("\nfig11, same run: plain %.1f s, with the budget %.1f s, ratio %.2f (target <= 3)\n", s["plain"],
              s["budget"], s["budget"] / s["plain"]);
}

}  // namespace inim::bench
