#include "splats/splat_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "spectral/color.h"
#include "splats/splat_sh.h"

namespace inim {

namespace {

constexpr int kMaxKBuffer = 64;

struct KHit {
  float t;
  uint32_t prim;
  float alpha;
};
inline bool before(float ta, uint32_t ia, float tb, uint32_t ib) { return ta < tb || (ta == tb && ia < ib); }

// The intersect context carries one trace's k-buffer (Embree hands it to the callback).
struct KBufferContext {
  RTCIntersectContext ctx;  // first member: Embree sees only this
  float tNear, tFar;        // the query interval
  float lastT;              // hits must come strictly after (lastT, lastPrim)
  uint32_t lastPrim;
  int k, count;
  KHit hits[kMaxKBuffer];

  // Keeps the k nearest hits, sorted by (t, prim).
  void insert(const KHit& h) {
    if (count == k && !before(h.t, h.prim, hits[k - 1].t, hits[k - 1].prim)) return;
    for (int j = 0; j < count; ++j)
      if (hits[j].prim == h.prim) return;  // a primitive met twice by the traversal
    int j = count < k ? count++ : k - 1;
    for (; j > 0 && before(h.t, h.prim, hits[j - 1].t, hits[j - 1].prim); --j) hits[j] = hits[j - 1];
    hits[j] = h;
  }
};

void boundsFunc(const RTCBoundsFunctionArguments* args) {
  const SplatPrimitive& p = static_cast<const SplatPrimitive*>(args->geometryUserPtr)[args->primID];
  *args->bounds_o = RTCBounds{p.lo.x, p.lo.y, p.lo.z, 0.0f, p.hi.x, p.hi.y, p.hi.z, 0.0f};
}

// Accepts the primitive into the k-buffer when its max-response sample counts; once the buffer
// is full, tfar shrinks to its farthest hit so the traversal skips farther boxes (a sample
// lies inside its ellipsoid, hence inside its box).
void intersectFunc(const RTCIntersectFunctionNArguments* args) {
  const SplatPrimitive& p = static_cast<const SplatPrimitive*>(args->geometryUserPtr)[args->primID];
  auto* kb = reinterpret_cast<KBufferContext*>(args->context);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const Vec3 o(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i), RTCRayN_org_z(ray, args->N, i));
    const Vec3 d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
    float t, alpha;
    splatMaxResponse(p, o, d, &t, &alpha);
    if (!(alpha >= kSplatMinAlpha) || !(t >= kb->tNear && t <= kb->tFar)) continue;
    if (!before(kb->lastT, kb->lastPrim, t, args->primID)) continue;
    kb->insert(KHit{t, args->primID, alpha});
    if (kb->count == kb->k) RTCRayN_tfar(ray, args->N, i) = std::min(RTCRayN_tfar(ray, args->N, i), kb->hits[kb->k - 1].t);
  }
}

void checkDevice(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree error ") + std::to_string(int(e)) + " in " + what);
}

}  // namespace

bool makeSplatPrimitive(const Gaussians& g, size_t i, SplatPrimitive* out) {
  const float opacity = std::min(g.opacity[i], 0.99f);
  if (!(opacity >= kSplatMinAlpha)) return false;
  const glm::mat3 R = quaternionToMatrix(g.rotation[i]);
  const Vec3 s = g.scale[i];
  glm::mat3 M = glm::transpose(R);  // then row j divided by s_j: S^-1 R^T
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) M[col][row] /= s[row];
  // Cut-off radius in the unit frame; the box half-extent along world axis a is
  // k * |row a of R S| (the ellipsoid's support function).
  const float k = std::sqrt(std::max(0.0f, 2.0f * std::log(255.0f * g.opacity[i])));
  Vec3 half;
  for (int a = 0; a < 3; ++a) half[a] = k * glm::length(Vec3(R[0][a] * s.x, R[1][a] * s.y, R[2][a] * s.z));
  half *= 1.0001f;  // float rounding must not cut the ellipsoid
  *out = SplatPrimitive{M, g.position[i], g.opacity[i], uint32_t(i), g.position[i] - half, g.position[i] + half};
  return true;
}

SplatField::SplatField(Gaussians g, const SplatFrame& frame, const SplatTraceSettings& settings)
    : g_(std::move(g)), frame_(frame), settings_(settings) {
  settings_.kBuffer = std::clamp(settings_.kBuffer, 1, kMaxKBuffer);
  prims_.reserve(g_.size());
  SplatPrimitive p;
  for (size_t i = 0; i < g_.size(); ++i)
    if (makeSplatPrimitive(g_, i, &p)) prims_.push_back(p);
  buildScene();
}

SplatField::~SplatField() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void SplatField::buildScene() {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
  if (!prims_.empty()) {
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(prims_.size()));
    rtcSetGeometryUserData(geom, prims_.data());
    rtcSetGeometryBoundsFunction(geom, boundsFunc, prims_.data());
    rtcSetGeometryIntersectFunction(geom, intersectFunc);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene_);
  checkDevice(device_, "building the splat scene");
}

SplatTraceResult SplatField::trace(const Vec3& o, const Vec3& d, float tNear, float tFar) const {
  SplatTraceResult r;
  if (prims_.empty() || !(tNear <= tFar)) return r;
  KBufferContext kb;
  rtcInitIntersectContext(&kb.ctx);
  kb.tNear = tNear;
  kb.tFar = tFar;
  kb.lastT = -kInfinity;
  kb.lastPrim = 0;
  kb.k = settings_.kBuffer;
  float T = 1.0f, depthSum = 0.0f;
  const Vec3 dirUnit = glm::normalize(d);
  const int shCount = g_.shPerSplat();
  for (;;) {
    kb.count = 0;
    RTCRayHit rh;
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    // Boxes of later hits contain their samples, which lie at or beyond lastT.
    rh.ray.tnear = std::max(tNear, std::nextafter(kb.lastT, -kInfinity));
    rh.ray.tfar = std::isinf(tFar) ? std::numeric_limits<float>::max() : tFar;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &kb.ctx, &rh);
    ++r.traces;
    for (int j = 0; j < kb.count; ++j) {
      const KHit& h = kb.hits[j];
      const SplatPrimitive& p = prims_[h.prim];
      const Vec3 c = splatShColour(g_.shDegree, &g_.sh[size_t(p.index) * size_t(shCount) * 3], dirUnit);
      const float w = T * h.alpha;
      r.encodedRgb += w * c;
      depthSum += w * h.t;
      T *= 1.0f - h.alpha;
      ++r.evaluated;
      if (T < settings_.minTransmittance) break;
    }
    if (T < settings_.minTransmittance || kb.count < kb.k) break;
    kb.lastT = kb.hits[kb.k - 1].t;
    kb.lastPrim = kb.hits[kb.k - 1].prim;
  }
  r.opacity = 1.0f - T;
  if (r.opacity > 0.0f) r.depth = depthSum / r.opacity;
  return r;
}

SplatTraceResult SplatField::traceFieldRay(const FieldRay& fr) const {
  // display = s R p + T: the splat-frame ray has origin R^T (o - T) / s, direction R^T d and
  // parameter t / s.
  const glm::mat3 toSplat = glm::transpose(frame_.rotation);
  const float invScale = 1.0f / frame_.scale;
  return trace(toSplat * (fr.o - frame_.translate) * invScale, toSplat * fr.d, fr.tNear * invScale, fr.tFar * invScale);
}

void SplatField::query(std::span<const FieldRay> rays, std::span<const SampledWavelengths>,
                       std::span<FieldSample> out, uint64_t) const {
  if (out.size() < rays.size()) throw std::invalid_argument("SplatField: output too small");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const SplatTraceResult r = traceFieldRay(rays[i]);
      FieldSample& s = out[i];
      s.rgb = Vec3(srgbDecode(r.encodedRgb.x), srgbDecode(r.encodedRgb.y), srgbDecode(r.encodedRgb.z));
      s.depth = r.depth * frame_.scale;
      s.opacity = r.opacity;
    }
  });
}

void SplatField::bounds(Point3& lo, Point3& hi) const {
  lo = Point3(kInfinity);
  hi = Point3(-kInfinity);
  for (const SplatPrimitive& p : prims_)
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? p.hi.x : p.lo.x, (c & 2) ? p.hi.y : p.lo.y, (c & 4) ? p.hi.z : p.lo.z);
      const Point3 q = frame_.toField(corner);
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  if (prims_.empty()) lo = hi = frame_.translate;
}

}  // namespace inim
