// view/: the default EIA shown on the default display, seen by the default camera, for each
// panel estimator and sample count, against references of the same estimator and of the point
// estimator.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "bench/bench_context.h"
#include "camera/camera_config.h"
#include "synthesis/eia_synthesis.h"
#include "display_view/display_model.h"
#include "display_view/view_camera.h"

namespace inim::bench {

namespace {

struct ViewContext {
  ViewBenchSettings settings;  // with referenceSpp and referenceGrid resolved
  std::unique_ptr<DisplayModel> dm;
  CameraDescription desc;
  std::unique_ptr<CameraModel> camera;
  std::map<std::pair<int, int>, Image> images;    // by (estimator, spp); estimator -1 - e: e's reference
  std::map<std::pair<int, int>, double> seconds;
  std::map<std::pair<int, int>, double> rssMiB;   // peak RSS of the process after the run
  double lensShapeSeconds[2] = {0.0, 0.0};        // view-lens/: spherical, even asphere
};
ViewContext& viewContext() {
  static ViewContext v;
  return v;
}

// Builds the display and camera on first use.
ViewContext& builtViewContext() {
  ViewContext& v = viewContext();
  if (!v.dm) {
    EiaContext& e = eiaContext();
    SynthesisSettings s;
    s.progress = false;
    s.spp = 4;
    SynthesisResult r = synthesizeEia(e.layout, e.display.panel, *sceneContext().scene, s);
    v.dm = std::make_unique<DisplayModel>(makeDisplayModel(e.display, e.layout, r.eia, "(default EIA)", MlaKind::Real));
    v.desc = loadCameraDescription(defaultCameraPath());
    DisplayPose pose;
    pose.distanceMm = v.desc.distanceMm;
    ViewCameraOptions co;
    co.width = v.settings.width;
    v.camera = makeViewCamera(v.desc, pose, co);
  }
  return v;
}

// Args: spp, estimator (int(PanelEstimator); -1 - e: the reference of estimator e).
void benchView(benchmark::State& state) {
  ViewContext& v = builtViewContext();
  ViewSettings s;
  s.spp = int(state.range(0));
  const int est = int(state.range(1));
  s.panelEstimator = est < 0 ? PanelEstimator(-1 - est) : PanelEstimator(est);
  s.progress = false;
  // References use another seed: the same seed would share their first samples (the same
  // Sobol points, the same Fresnel choices) with the runs they are compared with.
  if (est < 0) s.seed = 2;
  s.apertureGrid = est < 0 ? v.settings.referenceGrid : v.settings.grid;
  const std::pair<int, int> key(est, s.spp);
  for (auto _ : state) {
    ViewResult r = renderView(*v.camera, v.desc.sensor, *v.dm->mla, *v.dm->panel, v.dm->area, s);
    v.images[key] = std::move(r.image);
    v.seconds[key] = r.stats.seconds;
  }
  v.rssMiB[key] = peakRssMiB();
  state.counters["peak_RSS_MiB"] = peakRssMiB();
}

double meanOf(const Image& img) {
  double m = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) m += img.at(x, y, c);
  return m / (3.0 * img.width * img.height);
}

void printEstimatorRows(ViewContext& v, PanelEstimator e, const Image& ref, const Image* pointRef) {
  const int refSpp = v.settings.referenceSpp;
  const std::pair<int, int> refKey(-1 - int(e), refSpp);
  auto row = [&](int spp, const Image& img, double sec, double rss) {
    const double vsPoint = pointRef ? 100.0 * relativeRmse(img, *pointRef) : NAN;
    const double ratio = pointRef ? meanOf(img) / meanOf(*pointRef) : NAN;
    // Error x time: the relative MSE against the point reference (noise and bias) x seconds.
    const double cost = pointRef ? std::pow(vsPoint / 100.0, 2) * sec : NAN;
    std::printf("  %-10s %6d %10.2f %11.2f%% %13.2f%% %12.3e %12.4f %14.0f\n", panelEstimatorName(e), spp, sec,
                100.0 * relativeRmse(img, ref), vsPoint, cost, ratio, rss);
  };
  for (int spp : v.settings.spps) {
    const std::pair<int, int> key(int(e), spp);
    if (v.images.count(key)) row(spp, v.images[key], v.seconds[key], v.rssMiB[key]);
  }
  row(refSpp, ref, v.seconds[refKey], v.rssMiB[refKey]);
}

// The default view (point estimator, 4 spp) with the camera's lens given even-asphere terms on
// its first and last surfaces (arg 1), or as designed (arg 0): the asphere's cost in a whole view.
// The terms (r^4 .. r^8, a sag of ~1 um at the edge) keep the lens focusable like the original.
void benchViewLensShape(benchmark::State& state) {
  ViewContext& v = builtViewContext();
  CameraDescription desc = v.desc;
  if (state.range(0) == 1) {
    std::vector<LensSurface> s = desc.lens.surfaces();
    for (LensSurface* x : {&s.front(), &s.back()}) {
      const double r = x->semiAperture();
      x->asphere = {0.0, 1e-3 / std::pow(r, 4), -2e-4 / std::pow(r, 6), 1e-4 / std::pow(r, 8)};
    }
    desc.lens = LensSystem(s, desc.lens.name() + " (aspheric)", desc.lens.file());
    desc.lens.validate();
  }
  DisplayPose pose;
  pose.distanceMm = desc.distanceMm;
  ViewCameraOptions co;
  co.width = v.settings.width;
  const std::unique_ptr<CameraModel> camera = makeViewCamera(desc, pose, co);
  ViewSettings vs;
  vs.spp = 4;
  vs.progress = false;
  double seconds = 0.0;
  int runs = 0;
  for (auto _ : state) {
    ViewResult r = renderView(*camera, desc.sensor, *v.dm->mla, *v.dm->panel, v.dm->area, vs);
    benchmark::DoNotOptimize(r.image.data.data());
    seconds += r.stats.seconds, ++runs;
  }
  v.lensShapeSeconds[state.range(0)] = seconds / std::max(1, runs);
}

}  // namespace

double relativeRmse(const Image& a, const Image& ref) {
  double se = 0, sum = 0;
  size_t n = 0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      double r = ref.at(x, y, 0) + ref.at(x, y, 1) + ref.at(x, y, 2);
      if (!(r > 0.0)) continue;
      for (int c = 0; c < 3; ++c) {
        double d = double(a.at(x, y, c)) - ref.at(x, y, c);
        se += d * d;
        sum += ref.at(x, y, c);
      }
      n += 3;
    }
  return n && sum > 0 ? std::sqrt(se / double(n)) / (sum / double(n)) : 0.0;
}

void registerViewBenchmarks(const ViewBenchSettings& settings) {
  ViewContext& v = viewContext();
  v.settings = settings;
  const int maxSpp = *std::max_element(settings.spps.begin(), settings.spps.end());
  v.settings.referenceSpp = settings.referenceSpp > 0 ? settings.referenceSpp : 16 * maxSpp;
  v.settings.referenceGrid = settings.referenceGrid > 0 ? settings.referenceGrid : settings.grid;
  for (PanelEstimator e : settings.estimators)
    for (int spp : settings.spps)
      benchmark::RegisterBenchmark(("view/" + std::string(panelEstimatorName(e)) + "/spp:" + std::to_string(spp)).c_str(),
                                   benchView)
          ->Args({spp, int(e)})->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
  for (PanelEstimator e : settings.estimators)
    benchmark::RegisterBenchmark(("view/reference/" + std::string(panelEstimatorName(e))).c_str(), benchView)
        ->Args({v.settings.referenceSpp, -1 - int(e)})->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
  for (auto [name, aspheric] : {std::pair{"view-lens/spherical", 0}, {"view-lens/even-asphere", 1}})
    benchmark::RegisterBenchmark(name, benchViewLensShape)->Arg(aspheric)->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);
}

void printViewBenchResults() {
  ViewContext& v = viewContext();
  if (v.lensShapeSeconds[0] > 0.0 && v.lensShapeSeconds[1] > 0.0)
    std::printf("\nview with an even-asphere camera lens / the same lens spherical, time, same run: %.3f (target <= 1.3)\n",
                v.lensShapeSeconds[1] / v.lensShapeSeconds[0]);
  const int refSpp = v.settings.referenceSpp;
  const std::pair<int, int> pointRefKey(-1 - int(PanelEstimator::PointSample), refSpp);
  const Image* pointRef = v.images.count(pointRefKey) ? &v.images[pointRefKey] : nullptr;
  bool header = false;
  for (PanelEstimator e : v.settings.estimators) {
    const std::pair<int, int> refKey(-1 - int(e), refSpp);
    if (!v.images.count(refKey)) continue;
    const Image& ref = v.images[refKey];
    if (!header) {
      std::printf("\nview (real MLA, real lens, 0 deg) at %d x %d: time, RMSE relative to the mean against the same "
                  "estimator at %d spp (own ref) and against the point estimator at %d spp (point ref), mean / "
                  "point ref's mean, efficiency = relative MSE against the point ref x seconds (lower is better)\n",
                  ref.width, ref.height, refSpp, refSpp);
      std::printf("  %-10s %6s %10s %12s %14s %12s %12s %14s\n", "estimator", "spp", "seconds", "RMSE own ref",
                  "RMSE point ref", "MSE x s", "mean ratio", "peak RSS MiB");
      header = true;
    }
    printEstimatorRows(v, e, ref, pointRef);
  }
}

}  // namespace inim::bench
