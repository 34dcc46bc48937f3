#include "scene/scene_geometry.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace inim {

namespace {

// Embree reports API misuse and allocation failures through the device error; they are
// bugs or resource exhaustion, not user input.
void checkDevice(RTCDevice device, const char* what) {
  RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree error ") + std::to_string(int(e)) + " in " + what);
}

// ---- User-geometry callbacks for the exact quadrics -----------------------------------------

void boundsFunc(const RTCBoundsFunctionArguments* args) {
  const Shape* s = static_cast<const Shape*>(args->geometryUserPtr);
  RTCBounds* b = args->bounds_o;
  b->lower_x = s->lo.x;
  b->lower_y = s->lo.y;
  b->lower_z = s->lo.z;
  b->upper_x = s->hi.x;
  b->upper_y = s->hi.y;
  b->upper_z = s->hi.z;
}

void intersectFunc(const RTCIntersectFunctionNArguments* args) {
  const Shape* s = static_cast<const Shape*>(args->geometryUserPtr);
  const unsigned N = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, N);
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    if ((RTCRayN_mask(ray, N, i) & s->mask) == 0) continue;
    glm::dvec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    glm::dvec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    double tNear = RTCRayN_tnear(ray, N, i);
    double tFar = RTCRayN_tfar(ray, N, i);
    double t;
    int part;
    if (!intersectAnalytic(*s, o, d, tNear, tFar, &t, &part)) continue;
    float tf = float(t);
    if (!(tf < RTCRayN_tfar(ray, N, i))) continue;  // rounding must not grow tfar
    RTCRayN_tfar(ray, N, i) = tf;
    // Ng is recomputed exactly by surfaceAt(); pass a cheap placeholder.
    RTCHitN_Ng_x(hit, N, i) = 0.0f;
    RTCHitN_Ng_y(hit, N, i) = 0.0f;
    RTCHitN_Ng_z(hit, N, i) = 1.0f;
    RTCHitN_u(hit, N, i) = float(part);
    RTCHitN_v(hit, N, i) = 0.0f;
    RTCHitN_primID(hit, N, i) = args->primID;
    RTCHitN_geomID(hit, N, i) = args->geomID;
    RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
  }
}

void occludedFunc(const RTCOccludedFunctionNArguments* args) {
  const Shape* s = static_cast<const Shape*>(args->geometryUserPtr);
  const unsigned N = args->N;
  RTCRayN* ray = args->ray;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    if ((RTCRayN_mask(ray, N, i) & s->mask) == 0) continue;
    glm::dvec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    glm::dvec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    double t;
    int part;
    if (intersectAnalytic(*s, o, d, RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i), &t, &part))
      RTCRayN_tfar(ray, N, i) = -std::numeric_limits<float>::infinity();
  }
}

inline void fillRay(RTCRay& r, const Ray& ray, uint32_t mask) {
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = ray.tMin;
  r.tfar = ray.tMax;
  r.time = 0.0f;
  r.mask = mask;
  r.id = 0;
  r.flags = 0;
}

// Creates the Embree geometry of shape s (triangles or user geometry) and attaches it to
// `scene` under ID `id`.
void attachShape(RTCDevice device, RTCScene scene, Shape& s, unsigned id) {
  RTCGeometry g;
  if (s.type == ShapeType::Mesh) {
    g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), s.P.size()));
    for (size_t k = 0; k < s.P.size(); ++k) {
      v[3 * k] = s.P[k].x;
      v[3 * k + 1] = s.P[k].y;
      v[3 * k + 2] = s.P[k].z;
    }
    unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), s.numTriangles()));
    for (size_t k = 0; k < s.indices.size(); ++k) idx[k] = s.indices[k];
  } else {
    g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, &s);
    rtcSetGeometryBoundsFunction(g, boundsFunc, &s);
    rtcSetGeometryIntersectFunction(g, intersectFunc);
    rtcSetGeometryOccludedFunction(g, occludedFunc);
  }
  rtcSetGeometryMask(g, s.mask);
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene, g, id);
  rtcReleaseGeometry(g);
}

}  // namespace

SceneGeometry::SceneGeometry(std::vector<Shape> shapes) : shapes_(std::move(shapes)) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  lo_ = Point3(kInfinity);
  hi_ = Point3(-kInfinity);
  for (size_t i = 0; i < shapes_.size(); ++i) {
    Shape& s = shapes_[i];
    attachShape(device_, scene_, s, unsigned(i));
    if (s.mask & kMaskFilter) {
      if (!filterScene_) {
        filterScene_ = rtcNewScene(device_);
        rtcSetSceneFlags(filterScene_, RTC_SCENE_FLAG_ROBUST);
      }
      attachShape(device_, filterScene_, s, unsigned(i));
      filterLo_ = glm::min(filterLo_, s.lo);
      filterHi_ = glm::max(filterHi_, s.hi);
    }
    lo_ = glm::min(lo_, s.lo);
    hi_ = glm::max(hi_, s.hi);
  }
  if (filterScene_) {
    // Bounds of the filters, padded for rounding.
    Vec3 pad = 1e-5f * (glm::abs(filterLo_) + glm::abs(filterHi_)) + 1e-30f;
    filterLoPad_ = filterLo_ - pad;
    filterHiPad_ = filterHi_ + pad;
  }
  rtcCommitScene(scene_);
  if (filterScene_) rtcCommitScene(filterScene_);
  checkDevice(device_, "scene build");
  if (shapes_.empty()) {
    lo_ = hi_ = Point3(0.0f);
    extent_ = 1.0f;
  } else {
    extent_ = glm::length(hi_ - lo_);
    if (!(extent_ > 0.0f) || !std::isfinite(extent_)) extent_ = 1.0f;
  }
}

SceneGeometry::~SceneGeometry() {
  if (filterScene_) rtcReleaseScene(filterScene_);
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void SceneGeometry::bounds(Point3* lo, Point3* hi) const {
  *lo = lo_;
  *hi = hi_;
}

bool SceneGeometry::intersectT(const Ray& ray, float* t, uint32_t* shape, uint32_t mask) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  fillRay(rh.ray, ray, mask);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  *t = rh.ray.tfar;
  *shape = rh.hit.geomID;
  return true;
}

void SceneGeometry::toEmbree(const Ray& ray, uint32_t mask, RTCRay* r) { fillRay(*r, ray, mask); }

bool SceneGeometry::hitFromEmbree(const Ray& ray, const RTCRayHit& rh, Hit* hit) const {
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const Shape& s = shapes_[rh.hit.geomID];
  hit->t = rh.ray.tfar;
  hit->shape = rh.hit.geomID;
  if (s.type == ShapeType::Mesh)
    surfaceAt(s, ray, hit->t, rh.hit.primID, 0, rh.hit.u, rh.hit.v, hit);
  else
    surfaceAt(s, ray, hit->t, 0, int(rh.hit.u), 0.0f, 0.0f, hit);
  return true;
}

bool SceneGeometry::intersect(const Ray& ray, Hit* hit, uint32_t mask) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  fillRay(rh.ray, ray, mask);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  return hitFromEmbree(ray, rh, hit);
}

bool SceneGeometry::mayHitFilter(const Ray& ray) const {
  if (!filterScene_) return false;
  const Vec3 &lo = filterLoPad_, &hi = filterHiPad_;
  if (std::isfinite(ray.tMax)) {
    // Segment vs box by separating axes (no divisions): the box axes, then the 3 axes
    // perpendicular to the segment and each box axis.
    Point3 a = ray.at(ray.tMin), b = ray.at(ray.tMax);
    Vec3 c = 0.5f * (a + b) - 0.5f * (lo + hi), h = 0.5f * (b - a), e = 0.5f * (hi - lo);
    Vec3 ah = glm::abs(h);
    if (std::abs(c.x) > e.x + ah.x || std::abs(c.y) > e.y + ah.y || std::abs(c.z) > e.z + ah.z)
      return false;
    if (std::abs(c.y * h.z - c.z * h.y) > e.y * ah.z + e.z * ah.y + 1e-6f * glm::dot(ah, e)) return false;
    if (std::abs(c.z * h.x - c.x * h.z) > e.x * ah.z + e.z * ah.x + 1e-6f * glm::dot(ah, e)) return false;
    if (std::abs(c.x * h.y - c.y * h.x) > e.x * ah.y + e.y * ah.x + 1e-6f * glm::dot(ah, e)) return false;
    return true;
  }
  float t0 = ray.tMin, t1 = ray.tMax;
  for (int a = 0; a < 3; ++a) {
    if (ray.d[a] == 0.0f) {
      if (ray.o[a] < lo[a] || ray.o[a] > hi[a]) return false;
      continue;
    }
    float inv = 1.0f / ray.d[a];
    float tn = (lo[a] - ray.o[a]) * inv, tf = (hi[a] - ray.o[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf * (1.0f + 4e-7f));
    if (t0 > t1) return false;
  }
  return true;
}

bool SceneGeometry::intersectFilter(const Ray& ray, Hit* hit) const {
  if (!filterScene_) return false;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  fillRay(rh.ray, ray, kMaskAll);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(filterScene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const Shape& s = shapes_[rh.hit.geomID];
  hit->t = rh.ray.tfar;
  hit->shape = rh.hit.geomID;
  if (s.type == ShapeType::Mesh)
    surfaceAt(s, ray, hit->t, rh.hit.primID, 0, rh.hit.u, rh.hit.v, hit);
  else
    surfaceAt(s, ray, hit->t, 0, int(rh.hit.u), 0.0f, 0.0f, hit);
  return true;
}

bool SceneGeometry::occluded(const Ray& ray, uint32_t mask) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  fillRay(r, ray, mask);
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0.0f;
}

}  // namespace inim
