// place/: the placement page's server side (src/place/place_session.h), from a change of state
// to its level-0 preview ready (one query ray per lenslet, PNG encoded), as the page sees it
// over HTTP less the transport: the default scene, the shipped Gaussian splats, and a trained
// model when --field-model gives one. Each iteration moves the field 1 mm in z and back, so
// every preview is new; the diagram the worker draws next competes with it, as it does live.
// Target: <= 100 ms per update (10 updates per second) on 2 cores.
#include <filesystem>
#include <memory>
#include <unistd.h>

#include "bench/bench_context.h"
#include "core/output_file.h"
#include "fields/field_factory.h"
#include "place/place_preview.h"
#include "place/place_session.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"

namespace inim::bench {

namespace {

void placeLoop(benchmark::State& state, const std::string& fieldPath) {
  const auto out = std::filesystem::temp_directory_path() / ("inim-bench-place-" + std::to_string(::getpid()));
  PlaceOptions o;
  o.fieldPath = fieldPath;
  o.outDir = out.string();
  PlaceSession session(o);
  const Json start = session.state()["placement"]["translate_mm"];
  std::vector<double> serverMs;
  int i = 0;
  for (auto _ : state) {
    Json t = start;
    t[2] = start[2].get<double>() + ((i++ & 1) ? 0.0 : 1.0);
    const Json s = session.putState(Json{{"placement", {{"translate_mm", t}}}}.dump());
    const ImageAnswer a = session.image(ImageKind::Level0, s["revision"].get<uint64_t>(), std::chrono::seconds(60));
    if (a.status != ImageAnswer::Status::Ready) state.SkipWithError("the preview did not come");
    serverMs.push_back(a.serverMs);
  }
  std::sort(serverMs.begin(), serverMs.end());
  if (!serverMs.empty()) state.counters["server_median_ms"] = serverMs[serverMs.size() / 2];
  state.counters["updates/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  std::error_code ec;
  std::filesystem::remove_all(out, ec);
}

// The level-0 render alone (no worker, no PNG), and the diagram alone, on the default display.
void previewLoop(benchmark::State& state, const std::string& fieldPath, bool diagram) {
  const LoadedField f = loadField(fieldPath, "field");
  const Transform toDisplay = resolvePlacement(f.placement, {}).toDisplay();
  const EiLayout& L = eiaContext().layout;
  for (auto _ : state) {
    if (diagram) {
      PreviewSettings ps;
      ps.width = 900;
      benchmark::DoNotOptimize(renderPlacementPreview(L, *f.field, toDisplay, kDefaultVcpMm, ps).image.data.data());
    } else {
      benchmark::DoNotOptimize(renderPlacePreview(L, *f.field, toDisplay, kDefaultVcpMm, {}).image.data.data());
    }
  }
}

}  // namespace

void registerPlaceBenchmarks(const std::string& modelPath, double minTime) {
  auto reg = [minTime](const std::string& name, std::string path) {
    benchmark::RegisterBenchmark(name.c_str(), [path](benchmark::State& s) { placeLoop(s, path); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  };
  benchmark::RegisterBenchmark("place/level0-render/paper-fig7", [](benchmark::State& s) {
    previewLoop(s, defaultScenePath(), false);
  })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  benchmark::RegisterBenchmark("place/diagram-render/paper-fig7", [](benchmark::State& s) {
    previewLoop(s, defaultScenePath(), true);
  })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  if (!modelPath.empty())
    benchmark::RegisterBenchmark("place/level0-render/model", [modelPath](benchmark::State& s) {
      previewLoop(s, modelPath, false);
    })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  reg("place/level0-update/paper-fig7", defaultScenePath());
  reg("place/level0-update/guitar-splats", dataPath("scenes/splats/guitar.compressed.ply"));
  if (!modelPath.empty()) reg("place/level0-update/model", modelPath);
}

}  // namespace inim::bench
