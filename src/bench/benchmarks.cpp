#include "bench/benchmarks.h"

#include <unistd.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bench/bench_context.h"
#include "core/parallel.h"
#include "field_files/field_factory.h"

namespace inim {

namespace {

// Console output as usual, and the runs kept for the ratio table.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  RecordingReporter() : ConsoleReporter(isatty(STDOUT_FILENO) ? OO_ColorTabular : OO_Tabular) {}
  std::map<std::string, double> raysPerSecond;
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const auto& r : runs) {
      auto it = r.counters.find("rays/s");
      if (it != r.counters.end() && r.run_type == Run::RT_Iteration)
        raysPerSecond[r.run_name.function_name] = it->second.value;
    }
  }
};

void printRatios(std::map<std::string, double>& rps) {
  auto ratio = [&](const char* a, const char* b) {
    if (rps.count(a) && rps.count(b) && rps[b] > 0) std::printf("  %-36s / %-22s = %.3f\n", a, b, rps[a] / rps[b]);
  };
  std::printf("\nRatios of rays/s, same run:\n");
  ratio("query/inim-hit", "query/bare-embree");
  ratio("query/inim-field", "query/bare-embree");
  ratio("eia-query/inim-field", "eia-query/bare-embree");
  ratio("eia/paper-fig7-default-display-1spp", "eia-query/bare-embree");
  ratio("splats/guitar-query-960x540", "splats/guitar-bare-embree-boxes-960x540");
  ratio("mla/stack-one-layer", "mla/real-one-layer");
  ratio("mla/stack-two-layers", "mla/real-one-layer");
  ratio("eia/two-layers-traced-chief-rays", "eia/one-layer-pinhole-rays");
  ratio("lens/trace-even-asphere", "lens/trace-spherical");
}

}  // namespace

void runBenchmarks(const BenchSettings& settings) {
  bench::registerRadianceBenchmarks(settings.radiance);
  bench::registerQueryBenchmarks(settings.minTime);
  bench::registerViewBenchmarks(settings.view);
  bench::registerReferenceBenchmarks();
  bench::registerFig11Benchmarks();
  bench::registerSweepBenchmarks();
  bench::registerSplatBenchmarks(settings.minTime);
  bench::registerSceneBenchmarks();
  bench::registerMlaBenchmarks(settings.minTime);
  bench::registerLensBenchmarks(settings.minTime);
  bench::registerPlaceBenchmarks(settings.radiance, settings.minTime);
  // Debian builds libbenchmark without NDEBUG, so it prints a DEBUG warning; inim itself is a
  // Release build (see the header line below).
  std::string filterArg = "--benchmark_filter=" + settings.filter;
  std::vector<char*> args = {const_cast<char*>("inim bench"), filterArg.data()};
  int argc = int(args.size());
  benchmark::Initialize(&argc, args.data());
  std::printf("inim %s (%s build); threads: %d; scene: %s; %zu camera rays (1920x1080, 1 per pixel) for query/*\n",
              INIM_VERSION, INIM_BUILD_TYPE, settings.threads > 0 ? settings.threads : hardwareThreads(),
              defaultScenePath().c_str(), bench::sceneContext().rays.size());
  RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  printRatios(reporter.raysPerSecond);
  bench::printRadianceBenchResults();
  bench::printViewBenchResults();
  bench::printReferenceBenchResults();
  bench::printFig11BenchResults();
  bench::printSweepBenchResults();
}

}  // namespace inim
