// inim bench: speed benchmarks on Google Benchmark. Ratios are taken between benchmarks of
// the same run (these machines are shared and noisy, so absolute times drift).
//
//   render/paper-fig7      the full default render (1920x1080, 16 spp, direct lighting)
//   query/bare-embree      rtcIntersect1 over the camera rays of that image, nothing else
//   query/inim-hit         the same rays through inim's intersection (full surface data)
//   query/inim-field       the same rays through Field::query (radiance, direct lighting)
//   eia/paper-fig7         full orthoscopic EIA of the default display (6,215,625 rays, 1 spp)
//   eia-query/bare-embree  rtcIntersect1 over that EIA's 6.2M query rays
//   eia-query/inim-field   the same query rays through Field::query
//   view/E/spp:N           `inim view` of the default EIA (real MLA, real lens, 0 deg) at
//                          --view-width, N spp (--view-spp), panel estimator E = point,
//                          footprint or quadrature (--view-estimators); view/reference/E
//                          is the same estimator at --view-ref-spp (default 16x the largest N,
//                          seed 2; aperture table grid --view-ref-grid, default --view-grid). The
//                          table after the run gives each one's RMSE against its own reference
//                          (noise) and against the point estimator's reference (noise + bias),
//                          relative to the reference's mean, and the ratio of the means
#include <benchmark/benchmark.h>
#include <unistd.h>
#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <regex>
#include <sys/resource.h>
#include <vector>

#include "display/display.h"
#include "display/ei_layout.h"
#include "rays/pinhole_rays.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/orthoscopic.h"
#include "camera/camera_config.h"
#include "view/display_model.h"
#include "view/view_camera.h"
#include "view/view_renderer.h"

#include "cli/bench_radiance.h"
#include "cli/commands.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "camera/fov_camera.h"
#include "render/renderer.h"
#include "scene/analytic_scene.h"

namespace inim::cli {

namespace {

struct BenchContext {
  std::unique_ptr<AnalyticScene> scene;
  FovCameraSettings cam;
  std::vector<FieldRay> rays;  // one camera ray per pixel of the render
  std::vector<SampledWavelengths> lambdas;
};

BenchContext& context() {
  static BenchContext ctx = [] {
    BenchContext c;
    c.scene = AnalyticScene::load(defaultScenePath());
    c.cam.width = 1920;
    c.cam.height = 1080;
    FovCameraModel camera(c.cam);
    c.rays.resize(size_t(c.cam.width) * c.cam.height);
    c.lambdas.resize(c.rays.size());
    for (int y = 0; y < c.cam.height; ++y)
      for (int x = 0; x < c.cam.width; ++x) {
        uint64_t id = uint64_t(y) * c.cam.width + x;
        Rng rng = Rng::forSample(1, id);
        Ray r;
        camera.generateRay(Vec2(x + rng.uniform(), y + rng.uniform()), Vec2(0.5f), 550.0f, r);
        c.rays[id] = {r.o, r.d, 0.0f, kInfinity, id, 0};
        c.lambdas[id] = SampledWavelengths::sampleVisible(rng.uniform());
      }
    return c;
  }();
  return ctx;
}

constexpr int64_t kChunk = 4096;

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

// The default display and its orthoscopic query rays (the VCP at the default distance).
struct EiaContext {
  Display display = loadDisplay(defaultDisplayPath());
  EiLayout layout = computeLayout(display);
  std::vector<FieldRay> queries;
  std::vector<SampledWavelengths> lambdas;
};

EiaContext& eiaContext() {
  static EiaContext ctx = [] {
    EiaContext c;
    RaySet rays = generatePinholeRays(c.layout);
    OrthoscopicQuery oq(Transform(), kDefaultVcpMm);
    c.queries.resize(rays.size());
    c.lambdas.resize(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      Ray r = rays.ray(i);
      c.queries[i] = oq.make(Point3d(r.o), Vec3d(r.d), i, 0).ray;
      c.lambdas[i] = SampledWavelengths::sampleVisible(Rng::forSample(1, i).uniform());
    }
    return c;
  }();
  return ctx;
}

void benchEia(benchmark::State& state) {
  BenchContext& c = context();
  EiaContext& e = eiaContext();
  SynthesisSettings s;
  s.autoExposure = true;
  s.progress = false;
  for (auto _ : state) {
    SynthesisResult r = synthesizeEia(e.layout, e.display.panel, *c.scene, s);
    benchmark::DoNotOptimize(r.eia.data.data());
  }
  state.counters["rays/s"] =
      benchmark::Counter(double(e.layout.numRays()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["peak_RSS_MiB"] = peakRssMiB();
}

void benchRender(benchmark::State& state) {
  BenchContext& c = context();
  RenderSettings rs;
  rs.spp = 16;
  rs.progress = false;
  FovCameraModel camera(c.cam);
  for (auto _ : state) {
    RenderResult r = renderField(*c.scene, camera, rs);
    benchmark::DoNotOptimize(r.image.data.data());
  }
  state.counters["rays/s"] = benchmark::Counter(double(c.cam.width) * c.cam.height * rs.spp,
                                                benchmark::Counter::kIsIterationInvariantRate);
}

void bareEmbreeLoop(benchmark::State& state, const std::vector<FieldRay>& rays) {
  BenchContext& c = context();
  RTCScene scene = c.scene->embreeScene();
  for (auto _ : state) {
    std::atomic<uint64_t> hits{0};
    parallelForRange(int64_t(rays.size()), [&](int64_t b, int64_t e) {
      RTCIntersectContext ictx;
      rtcInitIntersectContext(&ictx);
      uint64_t local = 0;
      for (int64_t i = b; i < e; ++i) {
        const FieldRay& fr = rays[size_t(i)];
        RTCRayHit rh;
        rh.ray.org_x = fr.o.x, rh.ray.org_y = fr.o.y, rh.ray.org_z = fr.o.z;
        rh.ray.dir_x = fr.d.x, rh.ray.dir_y = fr.d.y, rh.ray.dir_z = fr.d.z;
        rh.ray.tnear = fr.tNear, rh.ray.tfar = fr.tFar, rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ictx, &rh);
        local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
      hits += local;
    }, nullptr, kChunk);
    benchmark::DoNotOptimize(hits.load());
  }
  state.counters["rays/s"] = benchmark::Counter(double(rays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void benchInimHit(benchmark::State& state) {
  BenchContext& c = context();
  for (auto _ : state) {
    std::atomic<uint64_t> hits{0};
    parallelForRange(int64_t(c.rays.size()), [&](int64_t b, int64_t e) {
      uint64_t local = 0;
      Hit h;
      for (int64_t i = b; i < e; ++i) {
        const FieldRay& fr = c.rays[size_t(i)];
        local += c.scene->intersect(Ray{fr.o, fr.d, fr.tNear, fr.tFar}, h);
      }
      hits += local;
    }, nullptr, kChunk);
    benchmark::DoNotOptimize(hits.load());
  }
  state.counters["rays/s"] = benchmark::Counter(double(c.rays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void fieldLoop(benchmark::State& state, const std::vector<FieldRay>& rays,
               const std::vector<SampledWavelengths>& lambdas) {
  BenchContext& c = context();
  std::vector<FieldSample> out(rays.size());
  for (auto _ : state) {
    parallelForRange(int64_t(rays.size()), [&](int64_t b, int64_t e) {
      c.scene->query(std::span(rays).subspan(size_t(b), size_t(e - b)),
                     std::span<const SampledWavelengths>(lambdas).subspan(size_t(b), size_t(e - b)),
                     std::span(out).subspan(size_t(b), size_t(e - b)), 1);
    }, nullptr, kChunk);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["rays/s"] = benchmark::Counter(double(rays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void benchBareEmbree(benchmark::State& state) { bareEmbreeLoop(state, context().rays); }
void benchInimField(benchmark::State& state) { fieldLoop(state, context().rays, context().lambdas); }
void benchEiaBareEmbree(benchmark::State& state) { bareEmbreeLoop(state, eiaContext().queries); }
void benchEiaField(benchmark::State& state) {
  fieldLoop(state, eiaContext().queries, eiaContext().lambdas);
}

// The view sweep: the default EIA shown on the default display, seen by the default camera.
struct ViewContext {
  int width = 648;
  std::vector<int> spps = {1, 4, 16};
  std::vector<PanelEstimator> estimators = {PanelEstimator::PointSample, PanelEstimator::Footprint};
  int refSpp = 256;
  int grid = 16, refGrid = 16;  // aperture table grid (quadrature) of the runs and the references
  std::unique_ptr<DisplayModel> dm;
  CameraDescription desc;
  std::unique_ptr<CameraModel> camera;
  std::map<std::pair<int, int>, Image> images;    // by (estimator, spp); estimator -1 - e: e's reference
  std::map<std::pair<int, int>, double> seconds;
  std::map<std::pair<int, int>, double> rssMiB;   // peak RSS of the process after the run
};
ViewContext& viewContext() {
  static ViewContext v;
  return v;
}
// Builds the display and camera on first use (after --view-width has been applied).
ViewContext& builtViewContext() {
  ViewContext& v = viewContext();
  if (!v.dm) {
    EiaContext& e = eiaContext();
    SynthesisSettings s;
    s.autoExposure = true;
    s.progress = false;
    s.spp = 4;
    SynthesisResult r = synthesizeEia(e.layout, e.display.panel, *context().scene, s);
    v.dm = std::make_unique<DisplayModel>(makeDisplayModel(e.display, e.layout, r.eia, "(default EIA)", MlaKind::Real));
    v.desc = loadCameraDescription(defaultCameraPath());
    DisplayPose pose;
    pose.distanceMm = v.desc.distanceMm;
    ViewCameraOptions co;
    co.width = v.width;
    v.camera = makeViewCamera(v.desc, pose, co);
  }
  return v;
}

// Args: spp, estimator (int(PanelEstimator); -1 - e: the reference of estimator e, at refSpp).
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
  s.apertureGrid = est < 0 ? v.refGrid : v.grid;
  const std::pair<int, int> key(est, s.spp);
  for (auto _ : state) {
    ViewResult r = renderView(*v.camera, v.desc.sensor, *v.dm->mla, *v.dm->panel, v.dm->area, s);
    v.images[key] = std::move(r.image);
    v.seconds[key] = r.stats.seconds;
  }
  v.rssMiB[key] = peakRssMiB();
  state.counters["peak_RSS_MiB"] = peakRssMiB();
}

// RMSE of `a` against `ref` over the pixels where the reference has signal, relative to the
// reference's mean there.
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

// Console output as usual, and the runs kept for the ratio table.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  RecordingReporter()
      : ConsoleReporter(isatty(STDOUT_FILENO) ? OO_ColorTabular : OO_Tabular) {}
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

}  // namespace

void addBenchCommand(CLI::App& app) {
  struct Opts {
    std::string filter = ".*";
    double minTime = 0.5;
    int viewWidth = 648;
    std::vector<int> viewSpp = {1, 4, 16};
    std::vector<std::string> viewEstimators = {"point", "footprint", "quadrature"};
    int viewRefSpp = 0;
    int viewGrid = 16, viewRefGrid = 0;
    RadianceBenchOptions radiance;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand("bench", "Speed benchmarks (Google Benchmark) with ratios measured in one run");
  cmd->add_option("--filter", o->filter, "Regex of benchmarks to run")->capture_default_str();
  cmd->add_option("--min-time", o->minTime, "Minimum seconds per benchmark")->capture_default_str();
  cmd->add_option("--view-width", o->viewWidth, "Image width of the view/ benchmarks (2592 = the sensor)")
      ->capture_default_str();
  cmd->add_option("--view-spp", o->viewSpp, "Samples per pixel of the view/ benchmarks")
      ->delimiter(',')->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--view-estimators", o->viewEstimators, "Panel estimators of the view/ benchmarks")
      ->delimiter(',')->check(CLI::IsMember({"point", "footprint", "quadrature"}))->capture_default_str();
  cmd->add_option("--view-ref-spp", o->viewRefSpp,
                  "spp of view/reference (footprint estimator); 0: 16x the largest --view-spp")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("--view-grid", o->viewGrid, "Aperture table grid of the quadrature view/ runs")
      ->check(CLI::Range(2, 64))->capture_default_str();
  cmd->add_option("--view-ref-grid", o->viewRefGrid,
                  "Aperture table grid of their references (0: --view-grid; larger: the table's own error shows "
                  "in the RMSE)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  addRadianceBenchOptions(cmd, o->radiance);
  addRunOptions(cmd, o->run);
  cmd->callback([o]() {
    ThreadLimit threads(o->run.threads);
    registerRadianceBenchmarks(o->radiance);
    // Debian builds libbenchmark without NDEBUG, so it prints a DEBUG warning; inim itself
    // is a Release build (see the header line below).
    auto reg = [&](const char* name, void (*fn)(benchmark::State&), bool once) {
      auto* b = benchmark::RegisterBenchmark(name, fn)->UseRealTime()->Unit(benchmark::kMillisecond);
      if (once) b->Iterations(1);
      else b->MinTime(o->minTime);
    };
    reg("query/bare-embree", benchBareEmbree, false);
    reg("query/inim-hit", benchInimHit, false);
    reg("query/inim-field", benchInimField, false);
    reg("render/paper-fig7-1920x1080-16spp-direct", benchRender, true);
    reg("eia/paper-fig7-default-display-1spp", benchEia, true);
    reg("eia-query/bare-embree", benchEiaBareEmbree, false);
    reg("eia-query/inim-field", benchEiaField, false);
    viewContext().width = o->viewWidth;
    {
      ViewContext& v = viewContext();
      v.spps = o->viewSpp;
      v.estimators.clear();
      for (const auto& e : o->viewEstimators)
        parsePanelEstimator(e, v.estimators.emplace_back());
      const int maxSpp = *std::max_element(v.spps.begin(), v.spps.end());
      v.refSpp = o->viewRefSpp > 0 ? o->viewRefSpp : 16 * maxSpp;
      v.grid = o->viewGrid;
      v.refGrid = o->viewRefGrid > 0 ? o->viewRefGrid : o->viewGrid;
      for (PanelEstimator e : v.estimators)
        for (int spp : v.spps)
          benchmark::RegisterBenchmark(
              ("view/" + std::string(panelEstimatorName(e)) + "/spp:" + std::to_string(spp)).c_str(), benchView)
              ->Args({spp, int(e)})->Iterations(1)->UseRealTime()
              ->Unit(benchmark::kMillisecond);
      for (PanelEstimator e : v.estimators)
        benchmark::RegisterBenchmark(("view/reference/" + std::string(panelEstimatorName(e))).c_str(), benchView)
            ->Args({v.refSpp, -1 - int(e)})->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
    }
    std::string filterArg = "--benchmark_filter=" + o->filter;
    std::vector<char*> args = {const_cast<char*>("inim bench"), filterArg.data()};
    int argc = int(args.size());
    benchmark::Initialize(&argc, args.data());
    std::printf("inim %s (%s build); threads: %d; scene: %s; %zu camera rays (1920x1080, 1 per pixel) for query/*\n",
                INIM_VERSION, INIM_BUILD_TYPE, o->run.threads > 0 ? o->run.threads : hardwareThreads(), defaultScenePath().c_str(),
                context().rays.size());
    RecordingReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    auto& rps = reporter.raysPerSecond;
    auto ratio = [&](const char* a, const char* b) {
      if (rps.count(a) && rps.count(b) && rps[b] > 0)
        std::printf("  %-36s / %-22s = %.3f\n", a, b, rps[a] / rps[b]);
    };
    std::printf("\nRatios of rays/s, same run:\n");
    ratio("query/inim-hit", "query/bare-embree");
    ratio("query/inim-field", "query/bare-embree");
    ratio("eia-query/inim-field", "eia-query/bare-embree");
    ratio("eia/paper-fig7-default-display-1spp", "eia-query/bare-embree");
    printRadianceBenchResults();
    ViewContext& v = viewContext();
    auto meanOf = [](const Image& img) {
      double m = 0.0;
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          for (int c = 0; c < 3; ++c) m += img.at(x, y, c);
      return m / (3.0 * img.width * img.height);
    };
    const std::pair<int, int> pointRefKey(-1 - int(PanelEstimator::PointSample), v.refSpp);
    const Image* pointRef = v.images.count(pointRefKey) ? &v.images[pointRefKey] : nullptr;
    bool header = false;
    for (PanelEstimator e : v.estimators) {
      const std::pair<int, int> refKey(-1 - int(e), v.refSpp);
      if (!v.images.count(refKey)) continue;
      const Image& ref = v.images[refKey];
      if (!header) {
        std::printf("\nview (real MLA, real lens, 0 deg) at %d x %d: time, RMSE relative to the mean against the same "
                    "estimator at %d spp (own ref) and against the point estimator at %d spp (point ref), mean / "
                    "point ref's mean\n", ref.width, ref.height, v.refSpp, v.refSpp);
        std::printf("  %-10s %6s %10s %12s %14s %12s %14s\n", "estimator", "spp", "seconds", "RMSE own ref",
                    "RMSE point ref", "mean ratio", "peak RSS MiB");
        header = true;
      }
      auto row = [&](int spp, const Image& img, double sec, double rss) {
        const double vsPoint = pointRef ? 100.0 * relativeRmse(img, *pointRef) : NAN;
        const double ratio = pointRef ? meanOf(img) / meanOf(*pointRef) : NAN;
        std::printf("  %-10s %6d %10.2f %11.2f%% %13.2f%% %12.4f %14.0f\n", panelEstimatorName(e), spp, sec,
                    100.0 * relativeRmse(img, ref), vsPoint, ratio, rss);
      };
      for (int spp : v.spps) {
        const std::pair<int, int> key(int(e), spp);
        if (v.images.count(key)) row(spp, v.images[key], v.seconds[key], v.rssMiB[key]);
      }
      row(v.refSpp, ref, v.seconds[refKey], v.rssMiB[refKey]);
    }
  });
}

}  // namespace inim::cli
