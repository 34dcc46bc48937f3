// render/, query/, eia/ and eia-query/: the default scene through inim's renderer, its
// intersection and its Field::query, against bare Embree on the same rays.
#include <embree3/rtcore.h>
#include <sys/resource.h>

#include <atomic>

#include "bench/bench_context.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "field_files/field_factory.h"
#include "rays/pinhole_rays.h"
#include "field_render/renderer.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/orthoscopic.h"

namespace inim::bench {

SceneContext& sceneContext() {
  static SceneContext ctx = [] {
    SceneContext c;
    c.scene = AnalyticScene::load(defaultScenePath());
    c.camera.width = 1920;
    c.camera.height = 1080;
    FovCameraModel camera(c.camera);
    c.rays.resize(size_t(c.camera.width) * c.camera.height);
    c.lambdas.resize(c.rays.size());
    for (int y = 0; y < c.camera.height; ++y)
      for (int x = 0; x < c.camera.width; ++x) {
        uint64_t id = uint64_t(y) * c.camera.width + x;
        Rng rng = Rng::forSample(1, id);
        Ray r;
        const float px = x + rng.uniform(), py = y + rng.uniform();
        camera.generateRay(Vec2(px, py), Vec2(0.5f), 550.0f, r);
        c.rays[id] = {r.o, r.d, 0.0f, kInfinity, id, 0};
        c.lambdas[id] = SampledWavelengths::sampleVisible(rng.uniform());
      }
    return c;
  }();
  return ctx;
}

// The default display and its orthoscopic query rays (the VCP at the default distance).
EiaContext& eiaContext() {
  static EiaContext ctx = [] {
    EiaContext c;
    c.display = loadDisplay(defaultDisplayPath());
    c.layout = computeLayout(c.display);
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

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

void setRaysPerSecond(benchmark::State& state, size_t rays) {
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsIterationInvariantRate);
}

namespace {

constexpr int64_t kChunk = 4096;

void benchEia(benchmark::State& state) { eiaLoop(state, *sceneContext().scene); }

void benchRender(benchmark::State& state) {
  SceneContext& c = sceneContext();
  RenderSettings rs;
  rs.spp = 16;
  rs.progress = false;
  FovCameraModel camera(c.camera);
  for (auto _ : state) {
    RenderResult r = renderField(*c.scene, camera, rs);
    benchmark::DoNotOptimize(r.image.data.data());
  }
  setRaysPerSecond(state, size_t(c.camera.width) * c.camera.height * size_t(rs.spp));
}

// The baseline: Embree's own rtcIntersect1, hit or miss only.
void bareEmbreeLoop(benchmark::State& state, const std::vector<FieldRay>& rays) {
  RTCScene scene = sceneContext().scene->embreeScene();
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
  setRaysPerSecond(state, rays.size());
}

void benchInimHit(benchmark::State& state) {
  SceneContext& c = sceneContext();
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
  setRaysPerSecond(state, c.rays.size());
}

void fieldLoop(benchmark::State& state, const std::vector<FieldRay>& rays,
               const std::vector<SampledWavelengths>& lambdas) {
  const AnalyticScene& scene = *sceneContext().scene;
  std::vector<FieldSample> out(rays.size());
  for (auto _ : state) {
    parallelForRange(int64_t(rays.size()), [&](int64_t b, int64_t e) {
      scene.query(std::span(rays).subspan(size_t(b), size_t(e - b)),
                  std::span<const SampledWavelengths>(lambdas).subspan(size_t(b), size_t(e - b)),
                  std::span(out).subspan(size_t(b), size_t(e - b)), 1);
    }, nullptr, kChunk);
    benchmark::DoNotOptimize(out.data());
  }
  setRaysPerSecond(state, rays.size());
}

void benchBareEmbree(benchmark::State& state) { bareEmbreeLoop(state, sceneContext().rays); }
void benchInimField(benchmark::State& state) { fieldLoop(state, sceneContext().rays, sceneContext().lambdas); }
void benchEiaBareEmbree(benchmark::State& state) { bareEmbreeLoop(state, eiaContext().queries); }
void benchEiaField(benchmark::State& state) { fieldLoop(state, eiaContext().queries, eiaContext().lambdas); }

}  // namespace

void eiaLoop(benchmark::State& state, const Field& field) {
  EiaContext& e = eiaContext();
  SynthesisSettings s;
  s.progress = false;
  for (auto _ : state) {
    SynthesisResult r = synthesizeEia(e.layout, e.display.panel, field, s);
    benchmark::DoNotOptimize(r.eia.data.data());
  }
  setRaysPerSecond(state, size_t(e.layout.numRays()));
  state.counters["peak_RSS_MiB"] = peakRssMiB();
}

void registerTimed(const char* name, void (*fn)(benchmark::State&), bool once, double minTime) {
  auto* b = benchmark::RegisterBenchmark(name, fn)->UseRealTime()->Unit(benchmark::kMillisecond);
  if (once) b->Iterations(1);
  else b->MinTime(minTime);
}

void registerQueryBenchmarks(double minTime) {
  auto reg = [&](const char* name, void (*fn)(benchmark::State&), bool once) { registerTimed(name, fn, once, minTime); };
  reg("query/bare-embree", benchBareEmbree, false);
  reg("query/inim-hit", benchInimHit, false);
  reg("query/inim-field", benchInimField, false);
  reg("render/paper-fig7-1920x1080-16spp-direct", benchRender, true);
  reg("eia/paper-fig7-default-display-1spp", benchEia, true);
  reg("eia-query/bare-embree", benchEiaBareEmbree, false);
  reg("eia-query/inim-field", benchEiaField, false);
}

}  // namespace inim::bench
