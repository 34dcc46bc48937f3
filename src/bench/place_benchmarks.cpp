// place/: the placement page's server side (src/place/place_session.h), from a change of state
// to its level-0 preview ready (one query ray per lenslet, PNG encoded), as the page sees it
// over HTTP less the transport: the default scene, the shipped Gaussian splats, and a trained
// model when --field-model gives one. Each iteration moves the field 1 mm in z and back, so
// every preview is new. No diagram is asked for, so none is drawn (the page asks for one at most
// every 400 ms during a drag, on a thread at the lowest priority).
// The model is placed as its own placement says, or as --field-scale, --field-rotate-deg and
// --field-translate-mm say (a field filling the display costs more than one beside empty space).
// Target: <= 100 ms per update (10 updates per second) on 2 cores.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <unistd.h>

#include "bench/bench_context.h"
#include "core/output_file.h"
#include "field_files/field_factory.h"
#include "place/place_preview.h"
#include "place/place_session.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"

namespace inim::bench {

namespace {

// The placement's keys that `given` sets, as the page would send them.
Json placementPatch(const PlacementOverride& given) {
  Json p = Json::object();
  auto put = [&p](const char* key, const std::optional<Vec3d>& v) {
    if (v) p[key] = {v->x, v->y, v->z};
  };
  put("scale", given.scale), put("rotate_deg", given.rotateDeg), put("translate_mm", given.translateMm);
  return p;
}

void placeLoop(benchmark::State& state, const std::string& fieldPath, const PlacementOverride& given) {
  const auto out = std::filesystem::temp_directory_path() / ("inim-bench-place-" + std::to_string(::getpid()));
  PlaceOptions o;
  o.fieldPath = fieldPath;
  o.outDir = out.string();
  PlaceSession session(o);
  if (const Json p = placementPatch(given); !p.empty()) session.putState(Json{{"placement", p}}.dump());
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

// Level 0's error: its image against the same rays through the full query (level 1 with one
// ray per lenslet and one wavelength sample, the same exposure), display-encoded in [0, 1].
void levelZeroError(benchmark::State& state, const EiLayout& L, const Field& field, const Transform& toDisplay) {
  const PreviewFrame cheap = renderPlacePreview(L, field, toDisplay, kDefaultVcpMm, {});
  PreviewRequest full;
  full.level = 1, full.raysPerSide = 1, full.wavelengthSamples = 1, full.exposure = cheap.exposure;
  const PreviewFrame exact = renderPlacePreview(L, field, toDisplay, kDefaultVcpMm, full);
  const size_t n = size_t(cheap.image.width) * cheap.image.height;
  std::vector<float> worst(n, 0.0f);
  double sum = 0.0;
  for (size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c) {
      const float d = std::abs(cheap.image.data[3 * p + c] - exact.image.data[3 * p + c]);
      sum += d, worst[p] = std::max(worst[p], d);
    }
  state.counters["err_mean"] = sum / (3.0 * double(n));
  state.counters["lenslets_off_0.1"] =
      double(std::count_if(worst.begin(), worst.end(), [](float w) { return w > 0.1f; })) / double(n);
}

// The level-0 render alone (no worker, no PNG) with its error, and the diagram alone, on the
// default display.
void previewLoop(benchmark::State& state, const std::string& fieldPath, bool diagram,
                 const PlacementOverride& given = {}) {
  const LoadedField f = loadField(fieldPath, "field");
  const Transform toDisplay = resolvePlacement(f.placement, given).toDisplay();
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
  if (!diagram) levelZeroError(state, L, *f.field, toDisplay);
}

}  // namespace

void registerPlaceBenchmarks(const RadianceBenchSettings& model, double minTime) {
  auto reg = [minTime](const std::string& name, std::string path, PlacementOverride given) {
    benchmark::RegisterBenchmark(name.c_str(), [path, given](benchmark::State& s) { placeLoop(s, path, given); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  };
  benchmark::RegisterBenchmark("place/level0-render/paper-fig7", [](benchmark::State& s) {
    previewLoop(s, defaultScenePath(), false);
  })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  benchmark::RegisterBenchmark("place/diagram-render/paper-fig7", [](benchmark::State& s) {
    previewLoop(s, defaultScenePath(), true);
  })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  if (!model.modelPath.empty())
    benchmark::RegisterBenchmark("place/level0-render/model", [model](benchmark::State& s) {
      previewLoop(s, model.modelPath, false, model.placement);
    })->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(minTime);
  reg("place/level0-update/paper-fig7", defaultScenePath(), {});
  reg("place/level0-update/guitar-splats", dataPath("scenes/splats/guitar.compressed.ply"), {});
  if (!model.modelPath.empty()) reg("place/level0-update/model", model.modelPath, model.placement);
}

}  // namespace inim::bench
