#pragma once
// The Embree side of an analytic scene: one RTCDevice and one committed RTCScene holding
// every shape (built-in triangles for meshes, user geometry for the exact quadrics).
// Geometry ID == index into shapes(). All queries are const and thread-safe.
#include <embree3/rtcore.h>

#include <vector>

#include "scene/shapes.h"

namespace inim {

class SceneGeometry {
 public:
  // Takes the finalized shapes; builds and commits the Embree scene.
  explicit SceneGeometry(std::vector<Shape> shapes);
  ~SceneGeometry();
  SceneGeometry(const SceneGeometry&) = delete;
  SceneGeometry& operator=(const SceneGeometry&) = delete;

  // Nearest hit in (ray.tMin, ray.tMax) among shapes whose mask shares a bit with `mask`.
  bool intersect(const Ray& ray, Hit* hit, uint32_t mask = kMaskAll) const;
  // Surface data for an Embree result of `ray` (false if it missed).
  bool hitFromEmbree(const Ray& ray, const RTCRayHit& rh, Hit* hit) const;
  // Fills an Embree ray from ours.
  static void toEmbree(const Ray& ray, uint32_t mask, RTCRay* r);
  // Only t/shape/prim/part/u/v (no surface evaluation): the bare Embree query.
  bool intersectT(const Ray& ray, float* t, uint32_t* shape, uint32_t mask = kMaskAll) const;
  bool occluded(const Ray& ray, uint32_t mask = kMaskOpaque) const;
  // Nearest thin filter (shapes with kMaskFilter) along ray, from a separate small BVH that
  // holds only the filters, so coloured shadow rays stay cheap. False if there are none.
  bool intersectFilter(const Ray& ray, Hit* hit) const;
  bool hasFilters() const { return filterScene_ != nullptr; }
  // Whether the segment ray (tMin, tMax) can meet any thin filter (bounding-box test).
  bool mayHitFilter(const Ray& ray) const;

  const std::vector<Shape>& shapes() const { return shapes_; }
  const Shape& shape(uint32_t i) const { return shapes_[i]; }
  RTCScene embreeScene() const { return scene_; }
  RTCDevice embreeDevice() const { return device_; }
  bool empty() const { return shapes_.empty(); }
  // Bounds of all shapes (a zero box at the origin for an empty scene).
  void bounds(Point3* lo, Point3* hi) const;
  // Size of the scene (bounding-box diagonal; 1 for an empty scene).
  float extent() const { return extent_; }

 private:
  std::vector<Shape> shapes_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCScene filterScene_ = nullptr;  // only the thin filters (or null)
  Point3 filterLo_{kInfinity}, filterHi_{-kInfinity};
  Point3 filterLoPad_{kInfinity}, filterHiPad_{-kInfinity};  // padded for rounding (mayHitFilter)
  Point3 lo_{0.0f}, hi_{0.0f};
  float extent_ = 1.0f;
};

}  // namespace inim
