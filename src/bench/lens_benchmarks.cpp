// lens/: camera lenses from files and through their aspheres.
//   lens/read-zmx-30-surfaces+schott  a 30-surface .zmx lens parsed, validated and analysed, plus
//                                     spectra/glass/SCHOTT.agf read whole (target: < 50 ms together)
//   lens/trace-even-asphere           real rays through the Thorlabs AL2520-A asphere (tests/data/zmx)
//   lens/trace-spherical              the same lens with its conic and aspheric terms removed; the
//                                     ratio of the two is the asphere's cost (target: within 1.3x)
#include <cmath>
#include <string>
#include <vector>

#include "bench/bench_context.h"
#include "camera/lens_loader.h"
#include "camera/zemax_lens.h"
#include "core/input_file.h"
#include "core/output_file.h"
#include "spectral/glass_catalog.h"

namespace inim::bench {

namespace {

// Fifteen weak N-BK7 biconvex elements behind a flat stop: 31 surfaces.
std::string thirtySurfaceZmx() {
  std::string t = "VERS 190513 80 123\nMODE SEQ\nNAME bench 30 surfaces\nUNIT MM X W X CM MR CPMM\nENPD 8\n"
                  "GCAT SCHOTT\nFTYP 0 0 1 3 0 0 0\nWAVM 1 0.4861 1\nWAVM 2 0.5876 1\nWAVM 3 0.6563 1\nPWAV 2\n"
                  "SURF 0\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ INFINITY\n"
                  "SURF 1\n  STOP\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ 2\n  DIAM 5 1 0 0 1 \"\"\n";
  int n = 2;
  for (int e = 0; e < 15; ++e) {
    t += "SURF " + std::to_string(n++) + "\n  TYPE STANDARD\n  CURV 2.0E-3 0 0 0 0 \"\"\n  DISZ 2\n"
         "  GLAS N-BK7 0 0 1.5168 64.17 0 0 0 0 0 0\n  DIAM 6 1 0 0 1 \"\"\n";
    t += "SURF " + std::to_string(n++) + "\n  TYPE STANDARD\n  CURV -2.0E-3 0 0 0 0 \"\"\n  DISZ 1\n  DIAM 6 1 0 0 1 \"\"\n";
  }
  t += "SURF " + std::to_string(n) + "\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ 0\n  DIAM 5 0 0 0 1 \"\"\n";
  return t;
}

void readZmxAndSchott(benchmark::State& state) {
  const std::string zmx = thirtySurfaceZmx();
  (void)MaterialCatalog::standard().glassCatalogues();  // the lookup table, loaded once per process
  for (auto _ : state) {
    GlassCatalog schott = loadAgf(dataPath("spectra/glass/SCHOTT.agf"));
    LensSystem lens = parseZmxLens(zmx, "bench.zmx");
    benchmark::DoNotOptimize(schott.glasses.data());
    benchmark::DoNotOptimize(lens.surfaces().data());
  }
}

struct TraceContext {
  LensSystem asphere, spherical;
  std::vector<LensRay> rays;  // from infinity, over the entrance pupil, fields up to 10 degrees
};

TraceContext& traceContext() {
  static TraceContext c = [] {
    TraceContext t;
    t.asphere = loadLens(dataPath("tests/data/zmx/AL2520-A.zmx"));
    std::vector<LensSurface> s = t.asphere.surfaces();
    for (LensSurface& x : s) x.asphere.clear(), x.conic = 0.0;
    t.spherical = LensSystem(s, "spherical", "bench");
    const double r = 0.45 * t.asphere.stopDiameterMm();
    for (int i = 0; i < 200000; ++i) {
      const double u = (i % 449) / 449.0, v = (i / 449 % 449) / 449.0, field = (i % 7) / 6.0 * 10.0 * M_PI / 180.0;
      const double rho = r * std::sqrt(u), phi = 2.0 * M_PI * v;
      t.rays.push_back({{rho * std::cos(phi), rho * std::sin(phi), -1.0}, {0.0, std::sin(field), std::cos(field)}});
    }
    return t;
  }();
  return c;
}

void traceLens(benchmark::State& state, const LensSystem& lens) {
  const TraceContext& c = traceContext();
  const std::vector<double> n = lens.indicesAt(550.0);
  size_t passed = 0;
  for (auto _ : state)
    for (LensRay r : c.rays) passed += lens.traceWithIndices(r, n.data(), TraceDirection::ObjectToImage).ok();
  benchmark::DoNotOptimize(passed);
  setRaysPerSecond(state, c.rays.size());
}

}  // namespace

void registerLensBenchmarks(double minTime) {
  registerTimed("lens/read-zmx-30-surfaces+schott", readZmxAndSchott, false, minTime);
  registerTimed("lens/trace-even-asphere", [](benchmark::State& s) { traceLens(s, traceContext().asphere); }, false, minTime);
  registerTimed("lens/trace-spherical", [](benchmark::State& s) { traceLens(s, traceContext().spherical); }, false, minTime);
}

}  // namespace inim::bench
