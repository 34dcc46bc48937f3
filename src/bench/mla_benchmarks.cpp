// mla/: camera rays traced backward through the default display's optics to the panel, by the
// exact single-lens tracer (RealMla) and by the stack tracer (StackMla) on the same MLA written
// as a one-layer stack and on a two-layer compound stack (the MLA and a mirrored copy 1 mm in
// front). The ratios (rays/s, same run) are the cost of describing a display as a stack, and
// of a second lens layer (the optical-stack issue's target: view through two layers within 2x).
// eia/: the default scene's EIA on the default display and on it with the two-layer stack (the
// chief rays traced through both layers, as `inim eia` makes them; target within 1.5x).
#include <memory>
#include <vector>

#include "bench/bench_context.h"
#include "core/rng.h"
#include "mla_optics/real_mla.h"
#include "mla_optics/stack_mla.h"
#include "runs/display_rays.h"
#include "synthesis/eia_synthesis.h"

namespace inim::bench {

namespace {

constexpr int kRays = 200000;

struct MlaContext {
  std::vector<Ray> rays;  // toward the panel from 10 mm above it, within 10 degrees, over the centre
  std::unique_ptr<MlaModel> real, stackOne, stackTwo;
  Display two;  // the default display with the two-layer stack
};

MlaContext& mlaContext() {
  static MlaContext c = [] {
    MlaContext m;
    EiaContext& e = eiaContext();
    const double g = e.display.reconstructionGapMm;
    m.real = RealMla::fromDisplay(e.display, e.layout, g, RealMlaOptions{FresnelMode::Weighted});
    Display one = e.display;
    one.stack = stackFromMla(one.mla, g);
    one.stackTraced = true;
    m.stackOne = std::make_unique<StackMla>(one, e.layout, g, FresnelMode::Weighted);
    Display two = one;
    StackLayer mirrored = two.stack->layers[1];
    std::swap(mirrored.back, mirrored.front);
    mirrored.back.radiusMm = -mirrored.back.radiusMm;
    StackLayer air = two.stack->layers[0];
    air.thicknessMm = 1.0;
    two.stack->layers.push_back(air);
    two.stack->layers.push_back(mirrored);
    m.stackTwo = std::make_unique<StackMla>(two, e.layout, g, FresnelMode::Weighted);
    m.two = two;
    Rng rng(1, 1);
    for (int i = 0; i < kRays; ++i) {
      Ray r;
      r.o = Point3(float(-20.0 + 40.0 * rng.uniformDouble()), float(-10.0 + 20.0 * rng.uniformDouble()), 10.0f);
      r.d = glm::normalize(Vec3(float(0.35 * (rng.uniformDouble() - 0.5)), float(0.35 * (rng.uniformDouble() - 0.5)), -1.0f));
      m.rays.push_back(r);
    }
    return m;
  }();
  return c;
}

void traceAll(benchmark::State& state, const MlaModel& mla) {
  const MlaContext& m = mlaContext();
  size_t reached = 0;
  for (auto _ : state) {
    for (const Ray& r : m.rays) {
      PanelArrival a;
      reached += mla.traceToPanel(r, 550.0f, FresnelMode::Weighted, nullptr, a);
    }
  }
  benchmark::DoNotOptimize(reached);
  state.counters["rays/s"] = benchmark::Counter(double(kRays), benchmark::Counter::kIsIterationInvariantRate);
}

// The default scene's EIA (1 spp) on display `d` with the default display's layout, along the
// display rays `inim eia` uses for it (made in every iteration): the pinhole rays for one thin
// layer, the chief rays traced through the stack for two.
void eiaAlong(benchmark::State& state, const Display& d) {
  const EiaContext& e = eiaContext();
  SynthesisSettings s;
  s.progress = false;
  for (auto _ : state) {
    const DisplayRays rays = displayRaysFor(d, e.layout, DisplayRayChoice{}, false);
    s.displayRays = rays.rays ? &*rays.rays : nullptr;
    SynthesisResult r = synthesizeEia(e.layout, d.panel, *sceneContext().scene, s);
    benchmark::DoNotOptimize(r.eia.data.data());
  }
  setRaysPerSecond(state, size_t(e.layout.numRays()));
}

}  // namespace

void registerMlaBenchmarks(double minTime) {
  // Whole EIAs: three runs each, the ratio of their rays/s the cost of a second lens layer.
  for (auto [name, fn] : {std::pair{"eia/one-layer-pinhole-rays", +[](benchmark::State& s) { eiaAlong(s, eiaContext().display); }},
                          {"eia/two-layers-traced-chief-rays", +[](benchmark::State& s) { eiaAlong(s, mlaContext().two); }}})
    benchmark::RegisterBenchmark(name, fn)->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(3);
  registerTimed("mla/real-one-layer", [](benchmark::State& s) { traceAll(s, *mlaContext().real); }, false, minTime);
  registerTimed("mla/stack-one-layer", [](benchmark::State& s) { traceAll(s, *mlaContext().stackOne); }, false, minTime);
  registerTimed("mla/stack-two-layers", [](benchmark::State& s) { traceAll(s, *mlaContext().stackTwo); }, false, minTime);
}

}  // namespace inim::bench
