#pragma once
// Shapes of an analytic scene. Spheres, disks and cylinders (a coin: side + caps) are exact
// quadrics intersected in their object space (double precision, numerically stable
// quadratic) through Embree user geometry; boxes, rectangles and OBJ meshes are world-space
// triangle meshes intersected by Embree's built-in triangles.
//
// Object space of the analytic shapes: sphere centred at 0 with radius r; disk in z = 0
// with radius r and normal +z; cylinder with axis z, radius r, z in [-h/2, h/2], optional
// caps. world = L * object + T (any invertible affine map: ellipsoids and elliptic
// cylinders are exact too).
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/transform.h"
#include "scene/texture.h"

namespace inim {

enum class ShapeType { Sphere, Disk, Cylinder, Mesh };

// Embree ray-mask bits: which rays see a shape.
constexpr uint32_t kMaskOpaque = 1u;   // blocks shadow rays
constexpr uint32_t kMaskFilter = 2u;   // thin filters: shadow rays pass with their transmittance
constexpr uint32_t kMaskAll = 0xFFFFFFFFu;

// Cylinder parts, reported as the hit's prim-local part.
enum CylinderPart : int { kCylSide = 0, kCylTop = 1, kCylBottom = 2 };

// Everything about a ray-surface hit that shading needs.
struct Hit {
  float t = kInfinity;  // ray parameter (distance when |d| = 1)
  Point3 p{0.0f};       // world position
  Vec3 ng{0.0f, 0.0f, 1.0f};  // unit geometric normal (outward for closed shapes)
  Vec3 ns{0.0f, 0.0f, 1.0f};  // unit shading normal, same side as ng
  SurfaceCoords tex;
  uint32_t shape = 0xFFFFFFFFu;
  uint32_t prim = 0;
  int part = 0;
  float eps = 0.0f;  // ray-offset distance for spawning rays here
};

struct Shape {
  ShapeType type = ShapeType::Mesh;
  int material = -1;
  int light = -1;      // index of the area light made from this shape, or -1
  int objectId = -1;   // the scene file's "id"
  std::string name;
  uint32_t mask = kMaskOpaque;
  bool needsUV = false;  // textured material: compute uv (and st on cylinder sides; needs trig)

  // Analytic shapes.
  double radius = 1.0, height = 1.0;
  bool caps = true;
  glm::dmat3 L{1.0}, Linv{1.0}, Nmat{1.0};  // linear part, inverse, inverse transpose
  glm::dvec3 T{0.0};
  double detL = 1.0;
  bool similarity = true;  // L = s * rotation (spheres stay spheres)
  double uniformScale = 1.0;

  // Meshes, in world space. N/UV/ST are per vertex and may be empty.
  std::vector<Vec3> P, N;
  std::vector<Vec2> UV, ST;
  std::vector<uint32_t> indices;

  // Rectangles (and rect lights): p = corner + u e1 + v e2, sampled without a table.
  bool parallelogram = false;
  Vec3 corner{0.0f}, e1{0.0f}, e2{0.0f}, pnormal{0.0f};

  // Derived by finalize().
  double area = 0.0;          // world-space surface area
  double objectArea = 0.0;    // analytic shapes: area in object space
  std::vector<double> triCdf;  // meshes: cumulative triangle areas, normalised
  std::vector<Vec3> triN;      // meshes: unit geometric normal per triangle
  Point3 lo{0.0f}, hi{0.0f};
  float extent = 0.0f;         // bounding-box diagonal

  void setTransform(const Transform& toWorld);
  // Computes area, sampling tables and bounds. Meshes: drops degenerate triangles and
  // returns how many were dropped.
  size_t finalize();
  size_t numTriangles() const { return indices.size() / 3; }
};

// ---- Exact analytic intersections in object space (double) --------------------------------
// Each returns the nearest t in (tMin, tMax), or false.
bool intersectSphereLocal(const glm::dvec3& o, const glm::dvec3& d, double r, double tMin,
                          double tMax, double* t);
bool intersectDiskLocal(const glm::dvec3& o, const glm::dvec3& d, double r, double tMin,
                        double tMax, double* t);
bool intersectCylinderLocal(const glm::dvec3& o, const glm::dvec3& d, double r, double h,
                            bool caps, double tMin, double tMax, double* t, int* part);
// World-space ray against an analytic shape (t in units of the world direction).
bool intersectAnalytic(const Shape& s, const glm::dvec3& o, const glm::dvec3& d, double tMin,
                       double tMax, double* t, int* part);

// Fills h (except t/shape) for a hit at parameter t on prim/part with barycentrics (u, v).
void surfaceAt(const Shape& s, const Ray& ray, float t, uint32_t prim, int part, float u,
               float v, Hit* h);
// Ray-offset distance for a point p on shape s: scaled to |p| and to the shape's size, so
// scenes at micrometre and metre scale both work.
inline float offsetEpsilon(const Point3& p, float extent) {
  float m = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
  return 2e-6f * m + 1e-7f * extent + 1e-30f;
}
// The origin of a ray leaving hit h in direction w: pushed off the surface to w's side.
inline Point3 spawnOrigin(const Hit& h, const Vec3& w) {
  return glm::dot(w, h.ng) >= 0.0f ? h.p + h.eps * h.ng : h.p - h.eps * h.ng;
}

// ---- Area sampling (emissive shapes) -------------------------------------------------------
struct ShapeSample {
  Point3 p;
  Vec3 n;          // unit outward normal at p
  float pdfArea;   // per world-space area
};
// u in [0,1)^2 picks the point, u3 in [0,1) picks the triangle / cylinder part.
ShapeSample sampleShapeArea(const Shape& s, Vec2 u, float u3);
// pdf per unit world area of sampleShapeArea at hit h on s.
float shapePdfArea(const Shape& s, const Hit& h);

}  // namespace inim
