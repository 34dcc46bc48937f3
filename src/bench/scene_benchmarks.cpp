// scene/: loading a scene description of N emissive spheres (JSON parse, strict reading, unique
// ids, materials, one area light each), N = 10,000, 100,000 and 1,000,000: linear in N, so the
// last is seconds, not the hours a look-up against every earlier object took; and of 100,000
// emissive rectangles (meshes, checked against the rect lights). Counter: objects/s.
#include <string>

#include "bench/bench_context.h"
#include "core/json_config.h"
#include "scene/scene_loader.h"

namespace inim::bench {

namespace {

// N emissive objects of `type` ("radius_mm": 0.1 or "size_mm": [0.1, 0.1]) on a 1000-wide grid.
std::string objectsJson(int n, const std::string& type, const std::string& size) {
  std::string text = R"({"units": "mm", "materials": {"glow": {"type": "emitter", "spectrum": "D65"}}, "objects": [)";
  text.reserve(size_t(n) * 120);
  for (int i = 0; i < n; ++i)
    text += std::string(i ? "," : "") + "\n{\"id\": " + std::to_string(i + 1) + ", \"type\": \"" + type + "\", " +
            size + ", \"translate_mm\": [" + std::to_string(i % 1000) + ", " + std::to_string(i / 1000) +
            ", -10], \"material\": \"glow\"}";
  return text + "]}\n";
}

void loadObjects(benchmark::State& state, int n, const std::string& type, const std::string& size) {
  const std::string text = objectsJson(n, type, size);
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
                                 [n](benchmark::State& s) { loadObjects(s, n, "sphere", R"("radius_mm": 0.1)"); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  benchmark::RegisterBenchmark("scene/load-rectangles/100000", [](benchmark::State& s) {
    loadObjects(s, 100000, "rectangle", R"("size_mm": [0.1, 0.1])");
  })->Unit(benchmark::kMillisecond)->Iterations(1);
}

}  // namespace inim::bench
