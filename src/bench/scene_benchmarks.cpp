// scene/: loading a scene description of N spheres (JSON parse, strict reading, unique ids,
// materials), N = 10,000, 100,000 and 1,000,000: linear in N, so the last is seconds, not the
// hours a look-up against every earlier object took. Counter: objects/s.
#include <string>

#include "bench/bench_context.h"
#include "core/json_config.h"
#include "scene/scene_loader.h"

namespace inim::bench {

namespace {

std::string spheresJson(int n) {
  std::string text = R"({"units": "mm", "materials": {"glow": {"type": "emitter", "spectrum": "D65"}}, "objects": [)";
  text.reserve(size_t(n) * 110);
  for (int i = 0; i < n; ++i)
    text += std::string(i ? "," : "") + "\n{\"id\": " + std::to_string(i + 1) +
            ", \"type\": \"sphere\", \"radius_mm\": 0.1, \"translate_mm\": [" + std::to_string(i % 1000) + ", " +
            std::to_string(i / 1000) + ", -10], \"material\": \"glow\"}";
  return text + "]}\n";
}

void loadSpheres(benchmark::State& state, int n) {
  const std::string text = spheresJson(n);
  for (auto _ : state) {
    const SceneDescription d = parseSceneDescription(parseJsonText(text, "spheres.json"), "spheres.json");
    benchmark::DoNotOptimize(d.objects.size());
  }
  state.counters["objects/s"] = benchmark::Counter(double(n), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

void registerSceneBenchmarks() {
  for (int n : {10000, 100000, 1000000})
    benchmark::RegisterBenchmark(("scene/load-spheres/" + std::to_string(n)).c_str(),
                                 [n](benchmark::State& s) { loadSpheres(s, n); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
}

}  // namespace inim::bench
