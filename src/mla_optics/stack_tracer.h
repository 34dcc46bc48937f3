#pragma once
// StackTracer: real rays through a flat optical stack (display/optical_stack.h), in double
// precision: refraction with n(lambda) at every surface (per ray's wavelength), Fresnel (off,
// weighted or stochastic), total internal reflection, rays crossing into neighbouring cells,
// aperture sheets and barrier walls that absorb (or reflect, with the walls' reflectance).
//
// Frame: the stack's (panel at z = 0, + toward the viewer); lattices put a lenslet (hole, cell)
// centre at (originX + offset, originY + offset) and repeat as the layer's lattice does
// (square: k P, l P; hex: rows P sqrt(3)/2 apart, odd rows shifted by P/2).
//
// Surfaces as height fields. Layer boundaries are planes, or a lens array's surface: in each
// lattice cell z = z_plane + sag(r), r the distance to the cell's centre, r clamped to the clear
// aperture's radius (flat land at the aperture edge's height beyond it). A ray meets such a
// surface by marching over the slab the surface fills, each step the larger of |f| / L (f the
// ray's height above the surface, L its Lipschitz bound: a step that cannot pass a root) and a
// floor of 1/128 of the pitch across or 1/16 of the slab's depth, then refining the bracketed
// root to 1e-13 mm (Illinois regula falsi). Only a double crossing within one floor step (a
// graze) can be missed; the cell-walking tracer of real_mla.h is exact for the one lens array
// it models, and tests check the two agree.
//
// Two lens arrays in contact: the air between their faces (curved on either side) is a region
// of its own, bounded by both; flat on both sides, the faces are a cemented interface.
//
// A lens array whose square (hex) clear aperture is smaller than its square (hex) cell, or a
// square aperture on a hex lattice: the cap inside the aperture, flat land outside it at the
// cap's height at the aperture's corners, and vertical walls between the cap's edge and the
// land, refracting like any face. The march splits at every line an aperture edge lies on; a
// change of sign across one is a wall hit.
//
// Curved stacks (display/curved_frame.h): every boundary is the same height field over its shell
// in the stack's frame (X, Y, W), and the panel a plane or a shell of its own. A ray meets a
// shell by the line-sphere (cylinder) equation, a lens surface by the same march over the parts
// of the ray inside its slab of shells, the Lipschitz bound widened by the map's stretch; normals
// are the height's gradient. Lens crossings are reported in the frame's
// arc coordinates. The curved array ends two pitches beyond its panel's edge (its shells are
// spheres or cylinders that would otherwise close around their centre); a ray that finds no
// surface there leaves the stack around its edge (StackExit::aroundEdge).
//
// A curved stack's barrier walls are the planes through the centre of curvature along its cells'
// borders on a square lattice; on a hex lattice a march finds where a ray leaves its cell's
// open hexagon in the arc coordinates.
//
// A curved array's walls between caps stand on planes through the centre of curvature for square
// apertures, as its barrier walls do. Apertures whose edges lie on no lattice of lines or planes
// (a hex aperture on a square lattice, a curved array's hex apertures) are found by stepping
// 1/256 of the pitch along the ray and bisecting where the point crosses an aperture's edge (a
// corner cut within one step is missed).
#include <memory>
#include <vector>

#include "core/geometry.h"
#include "core/rng.h"
#include "display/optical_stack.h"
#include "mla_optics/mla_model.h"

namespace inim {

struct StackExit {
  Point3d p{0.0};            // where the ray left the stack (its last event)
  Vec3d d{0.0};              // unit direction leaving the stack
  double throughput = 1.0;   // Fresnel (weighted mode) and wall reflectances
  int events = 0;            // surface interactions
  bool trapped = false;      // still inside after the most events allowed (guided by TIR)
  bool towardViewer = true;  // left through the front (else back through the panel plane)
  bool aroundEdge = false;   // a curved stack's: left around its edge, guided there by TIR
  // Where the ray last refracted at a lens surface (the lenslet that formed the image), in the
  // stack's frame (a curved stack's arc coordinates: its lattice's).
  bool crossedLens = false;
  double lensXMm = 0.0, lensYMm = 0.0;
};

class StackTracer {
 public:
  // Lattice points of every layer are placed relative to (originXMm, originYMm).
  StackTracer(const OpticalStack& stack, FresnelMode fresnel = FresnelMode::Off, double originXMm = 0.0,
              double originYMm = 0.0);
  ~StackTracer();  // in the .cpp, where Boundary and Region are complete
  StackTracer(StackTracer&&) noexcept;

  // Traces from `o` (inside the stack's z range, or on the panel plane z = 0 heading +z, or in
  // front of the stack heading -z) along unit `d` until the ray leaves the stack (true, `out`
  // holds where and which way) or is absorbed (false: an aperture sheet, a wall, too many
  // events). `rng` is needed for the stochastic Fresnel mode only.
  bool trace(const Point3d& o, const Vec3d& d, double lambdaNm, Rng* rng, StackExit& out) const {
    return trace(o, d, lambdaNm, fresnel_, rng, out);
  }
  // The same with another Fresnel mode than the tracer's own.
  bool trace(const Point3d& o, const Vec3d& d, double lambdaNm, FresnelMode fresnel, Rng* rng, StackExit& out) const;

  // The stack's highest point: its front plane, or above it the tips of a last surface that
  // bulges out toward the viewer (a concave front face's cell borders).
  double frontZ() const { return front_; }

 private:
  struct Boundary;
  struct Region;
  double boundaryZ(const Boundary& b, double x, double y) const;     // x, y in b's frame
  Vec3d boundaryNormal(const Boundary& b, double x, double y) const;  // unit, +z side up (flat)
  // World point p's height above boundary b along its frame's W; the unit normal there, up.
  double heightAbove(const Boundary& b, const Point3d& p) const;
  Vec3d boundaryNormalAt(const Boundary& b, const Point3d& p) const;
  bool hitCurvedBoundary(const Boundary& b, const Point3d& o, const Vec3d& d, double tMax, double& t,
                         Vec3d* wallNormal) const;
  void setCurvedExtent(const OpticalStack& s);
  // Where the ray meets boundary b within tMax; on a wall between a lens array's caps, its
  // horizontal normal in *wallNormal (else zero).
  bool hitBoundary(const Boundary& b, const Point3d& o, const Vec3d& d, double tMax, double& t,
                   Vec3d* wallNormal = nullptr) const;
  struct WallCrossing {
    double t;
    Vec3d normal;  // the aperture edge's outward normal, were the line an edge
  };
  std::vector<WallCrossing> wallCrossings(const Boundary& b, const Point3d& o, const Vec3d& d, double t0,
                                          double t1) const;
  std::vector<WallCrossing> curvedWallCrossings(const Boundary& b, const Point3d& o, const Vec3d& d, double t0,
                                                double t1) const;
  std::vector<WallCrossing> apertureCrossings(const Boundary& b, const Point3d& o, const Vec3d& d, double t0,
                                              double t1) const;
  bool hitWall(const Region& r, const Point3d& o, const Vec3d& d, double tMax, double& t, Vec3d& n) const;
  bool hitCurvedWall(const Region& r, const Point3d& o, const Vec3d& d, double tMax, double& t, Vec3d& n) const;
  bool hitCurvedHexWall(const Region& r, const Point3d& o, const Vec3d& d, double tMax, double cx, double cy, double& t,
                        Vec3d& n) const;
  bool passesSheet(const Region& r, const Point3d& a, const Point3d& b) const;
  double index(const Region& r, double lambdaNm) const;

  std::vector<Boundary> boundaries_;  // boundaries_[i] below region i, boundaries_[i + 1] above
  std::vector<Region> regions_;
  std::unique_ptr<Region> outside_;   // air in front of the stack
  FresnelMode fresnel_;
  // The stack's frames (flat when it is not curved), on the heap: boundaries point at them.
  std::unique_ptr<const CurvedFrame> array_, panel_;
  double top_ = 0.0, front_ = 0.0;
  double extentX_ = 1e300, extentY_ = 1e300;  // a curved array's half extent (arc lengths)
  int maxEvents_ = 64;
};

}  // namespace inim
