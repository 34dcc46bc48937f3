// splats/: the shipped Gaussian-splat scene (scenes/splats/guitar.compressed.ply, 90,854
// splats) as a Field, placed as `inim` places it: the default EIA (6.2 M display rays), a
// 960 x 540 render at 16 spp, and the bare Embree traversal of the same cut-off boxes (a box hit
// is accepted as is: no Gaussian evaluated, no k-buffer) on the render's camera rays. Counters:
// rays/s, and over the rays of the run the Gaussians composited and the traversals per ray.
#include <embree3/rtcore.h>

#include <atomic>

#include "bench/bench_context.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "field_files/field_factory.h"
#include "field_render/renderer.h"
#include "splats/splat_field.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/orthoscopic.h"

namespace inim::bench {

namespace {

struct SplatContext {
  LoadedField loaded;
  const SplatField* field = nullptr;
  FovCameraSettings camera;  // the render's: 960 x 540, the default pose
  std::vector<FieldRay> cameraRays;
};

SplatContext& splatContext() {
  static SplatContext ctx = [] {
    SplatContext c;
    c.loaded = loadField(dataPath("scenes/splats/guitar.compressed.ply"), "field");
    c.field = c.loaded.splats;
    FovCameraModel camera(c.camera);
    for (int y = 0; y < c.camera.height; ++y)
      for (int x = 0; x < c.camera.width; ++x) {
        Ray r;
        camera.generateRay(Vec2(x + 0.5f, y + 0.5f), Vec2(0.5f), 550.0f, r);
        c.cameraRays.push_back({r.o, r.d, 0.0f, kInfinity, uint64_t(y) * c.camera.width + x, 0});
      }
    return c;
  }();
  return ctx;
}

// Gaussians composited and Embree traversals per ray, over `rays` (every `stride`-th).
void setWorkPerRay(benchmark::State& state, const SplatField& f, const std::vector<FieldRay>& rays, size_t stride) {
  std::atomic<uint64_t> evaluated{0}, traces{0}, n{0};
  parallelForRange(int64_t((rays.size() + stride - 1) / stride), [&](int64_t b, int64_t e) {
    uint64_t ev = 0, tr = 0;
    for (int64_t i = b; i < e; ++i) {
      const SplatTraceResult r = f.traceFieldRay(rays[size_t(i) * stride]);
      ev += uint64_t(r.evaluated), tr += uint64_t(r.traces);
    }
    evaluated += ev, traces += tr, n += uint64_t(e - b);
  });
  state.counters["gaussians/ray"] = double(evaluated) / double(n);
  state.counters["traversals/ray"] = double(traces) / double(n);
}

void benchSplatEia(benchmark::State& state) {
  SplatContext& c = splatContext();
  eiaLoop(state, *c.loaded.field);
  setWorkPerRay(state, *c.field, eiaContext().queries, 16);
}

void benchSplatRender(benchmark::State& state) {
  SplatContext& c = splatContext();
  RenderSettings rs;
  rs.spp = 16;
  rs.progress = false;
  FovCameraModel camera(c.camera);
  for (auto _ : state) {
    RenderResult r = renderField(*c.loaded.field, camera, rs);
    benchmark::DoNotOptimize(r.image.data.data());
  }
  state.counters["rays/s"] = benchmark::Counter(double(c.cameraRays.size()) * rs.spp, benchmark::Counter::kIsIterationInvariantRate);
  setWorkPerRay(state, *c.field, c.cameraRays, 1);
}

// The boxes alone: an intersect callback that takes the box's entry point as the hit.
void boxOnlyIntersect(const RTCIntersectFunctionNArguments* args) {
  const SplatPrimitive& p = static_cast<const SplatPrimitive*>(args->geometryUserPtr)[args->primID];
  RTCRayHitN* rh = args->rayhit;
  RTCRayN* ray = RTCRayHitN_RayN(rh, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    float t0 = RTCRayN_tnear(ray, args->N, i), t1 = RTCRayN_tfar(ray, args->N, i);
    const float o[3] = {RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i), RTCRayN_org_z(ray, args->N, i)};
    const float d[3] = {RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i)};
    for (int a = 0; a < 3 && t0 <= t1; ++a) {
      const float inv = 1.0f / d[a];
      float ta = (p.lo[a] - o[a]) * inv, tb = (p.hi[a] - o[a]) * inv;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    if (!(t0 <= t1)) continue;
    RTCRayN_tfar(ray, args->N, i) = t0;
    RTCHitN_geomID(RTCRayHitN_HitN(rh, args->N), args->N, i) = args->geomID;
    RTCHitN_primID(RTCRayHitN_HitN(rh, args->N), args->N, i) = args->primID;
  }
}

void benchSplatBareEmbree(benchmark::State& state) {
  SplatContext& c = splatContext();
  const std::vector<SplatPrimitive>& prims = c.field->primitives();
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, unsigned(prims.size()));
  rtcSetGeometryUserData(geom, const_cast<SplatPrimitive*>(prims.data()));
  rtcSetGeometryBoundsFunction(geom, [](const RTCBoundsFunctionArguments* a) {
    const SplatPrimitive& p = static_cast<const SplatPrimitive*>(a->geometryUserPtr)[a->primID];
    *a->bounds_o = RTCBounds{p.lo.x, p.lo.y, p.lo.z, 0.0f, p.hi.x, p.hi.y, p.hi.z, 0.0f};
  }, const_cast<SplatPrimitive*>(prims.data()));
  rtcSetGeometryIntersectFunction(geom, boxOnlyIntersect);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  rtcCommitScene(scene);
  // The camera rays in the splat frame, as the field traces them.
  const SplatFrame& fr = c.field->frame();
  const glm::mat3 toSplat = glm::transpose(fr.rotation);
  for (auto _ : state) {
    std::atomic<uint64_t> hits{0};
    parallelForRange(int64_t(c.cameraRays.size()), [&](int64_t b, int64_t e) {
      RTCIntersectContext ictx;
      rtcInitIntersectContext(&ictx);
      uint64_t local = 0;
      for (int64_t i = b; i < e; ++i) {
        const FieldRay& r = c.cameraRays[size_t(i)];
        const Vec3 o = toSplat * (r.o - fr.translate) / fr.scale, d = toSplat * r.d;
        RTCRayHit rh;
        rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
        rh.ray.tnear = 0.0f, rh.ray.tfar = std::numeric_limits<float>::max(), rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ictx, &rh);
        local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
      hits += local;
    });
    benchmark::DoNotOptimize(hits.load());
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  state.counters["rays/s"] = benchmark::Counter(double(c.cameraRays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void benchSplatField(benchmark::State& state) {
  SplatContext& c = splatContext();
  std::vector<FieldSample> out(c.cameraRays.size());
  for (auto _ : state) {
    c.loaded.field->query(c.cameraRays, {}, out, 1);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["rays/s"] = benchmark::Counter(double(c.cameraRays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

void registerSplatBenchmarks(double minTime) {
  auto reg = [&](const char* name, void (*fn)(benchmark::State&), bool once) { registerTimed(name, fn, once, minTime); };
  reg("splats/guitar-eia-default-display", benchSplatEia, true);
  reg("splats/guitar-render-960x540-16spp", benchSplatRender, true);
  reg("splats/guitar-query-960x540", benchSplatField, false);
  reg("splats/guitar-bare-embree-boxes-960x540", benchSplatBareEmbree, false);
}

}  // namespace inim::bench
