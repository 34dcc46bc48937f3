#pragma once
// RealMla: the microlens array as refracting geometry (docs/design.md).
//
// Geometry. A lattice of identical lenslets (square, or hex with horizontal rows: "pointy-top"
// cells whose flat sides are vertical, rows P sqrt(3)/2 apart, odd rows shifted by P/2) on a
// plane-parallel substrate of centre thickness T (vertex to flat face). Each lenslet's cap is
// the conic sag z(r) = c r^2 / (1 + sqrt(1 - (1 + kappa) c^2 r^2)), c = 1/R, over its clear
// aperture A = aperture shape (square side a, circle diameter a, or hex flat-to-flat a in the
// cell's orientation) clipped to the lattice cell. Outside A (when A is smaller than the cell)
// the substrate is flat "land" at the height of A's lowest cap point (the sag s_max at A's
// farthest point from the centre); where the cap edge stands higher than the land there is a
// vertical wall. For a square aperture = pitch on a square lattice (the paper's MLA), or a hex
// one on a hex lattice, the caps meet their neighbours along the cell edges (no land, no
// walls); a circular aperture meets the land at its own edge (zero-height wall). The plate
// covers the bounding box of its `cols` x `rows` indexed lenslets plus `marginCells` more on
// every side (lenslets there are real but report index -1); a ray inside the substrate that
// reaches the plate's side is lost (absorbed by the edge), and so is a ray in air that meets
// the side. Beyond the plate rays travel in air.
//
// Orientation. curved-toward-viewer: the caps face +z (the viewer), the flat face the panel.
// curved-toward-panel: the caps face the panel.
//
// Reference plane (docs/design.md). The MLA sits so that every lenslet's object-side
// (panel-side) nodal point is on z = 0. Both sides are air, so nodal and principal points
// coincide: for a plano-convex lens of index n, the panel-side principal plane H is T/n inside
// the flat face (curved-toward-viewer) or at the cap vertex (curved-toward-panel); the
// viewer-side one, H', is at the vertex (curved-toward-viewer) or T/n inside the flat face
// (curved-toward-panel). Both cases give H at z = 0 and H' at z = T (n - 1)/n. n is n_d
// (587.56 nm) for placement, so the geometry does not depend on wavelength. Then:
//   - the gap g (panel at z = -g) is measured from H, so g = f puts the panel exactly in the
//     lenslets' front focal plane, and psi, L = g f / (g - f) hold with the thick-lens f;
//   - a paraxial ray from a panel point aimed at a lenslet's (x_c, y_c, 0) leaves the lenslet
//     parallel to itself (nodal property): the real model's paraxial chief ray has exactly the
//     pinhole ray's direction. The leaving ray passes through the rear nodal point N' =
//     (x_c, y_c, T (n - 1)/n) instead of (x_c, y_c, 0): a thick lens has two nodal points.
//     tests/mla_optics/test_real_mla.cpp (ReferencePlane*) proves both.
//   For the prototype (T = 1.5 mm, PMMA): curved-toward-viewer puts the flat face at
//   z = -1.006 mm and the vertices at z = +0.494 mm.
//
// Interfaces: Snell's law with n(lambda) from the material catalog (tabulated per 1 nm over
// 300-1000 nm, linear interpolation); unpolarised Fresnel reflectance R = (Rs + Rp)/2 and
// transmittance T = 1 - R (energy; the n^2 radiance factors cancel between two air spaces);
// total internal reflection; optional Beer-Lambert absorption exp(-alpha * path in glass).
// FresnelMode (mla_model.h) picks how R and T are used; Stochastic by default.
// Up to `maxEvents` surface interactions (refractions, reflections, TIR bounces) are traced;
// a ray still inside after that is lost. Every failure is a clean `false`: no NaN, no Inf and
// no unbounded loop, for any finite ray (grazing, parallel to the panel, on cell edges).
//
// Lenslet reported (PanelArrival::lensletK/L, MlaExit::capK/L): the cap the ray last refracted
// through, i.e. the lenslet that formed the image: curved-toward-panel, the cap it leaves
// through toward the panel; curved-toward-viewer, the cap it entered by (it leaves through
// the flat face, possibly under a neighbour). -1 when it crossed no cap (land, or beyond the
// indexed lenslets). traceToPanel ignores Ray::tMin / tMax; the ray must start in air.
//
// Cell traversal is exact: the ray is walked cell by cell across the slab that holds the caps
// (it is at most s_max thick), and in each cell its cap (a quadric: one closed-form root picked
// by crossing direction, so a ray never re-hits the surface it just left), land and walls are
// intersected. A ray that enters lenslet k's cap may therefore leave through lenslet k + 1's.
// Cells share their edges, the caps meet continuously there, and the per-cell intervals
// overlap by 1e-9 mm, so rays exactly on edges and corners never slip through.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/geometry.h"
#include "core/rng.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/mla_model.h"
#include "spectral/dispersion.h"

namespace inim {

// Unpolarised Fresnel reflectance R = (Rs + Rp) / 2 for light in index n1 meeting index n2 at
// incidence cosine cosi (clamped to [0, 1]); 1 beyond the critical angle (TIR). The
// transmittance is T = 1 - R.
double fresnelReflectance(double cosi, double n1, double n2);

struct RealMlaGeometry {
  Mla::Lattice lattice = Mla::Lattice::Square;
  Mla::Aperture aperture = Mla::Aperture::Square;
  Mla::Orientation orientation = Mla::Orientation::CurvedTowardViewer;
  double pitchMm = 1.0;       // lattice pitch P (centre to nearest centre)
  double apertureMm = 1.0;    // square side, circle diameter or hex flat-to-flat; <= pitch
  double radiusMm = 1.62;     // vertex radius of curvature R of the cap (> 0: convex)
  double conic = 0.0;         // kappa: 0 sphere, -1 paraboloid
  double thicknessMm = 1.5;   // centre thickness T, vertex to flat face
  // Centre of lenslet (0, 0) (the top-left one); lenslet (k, l) is k columns right, l rows
  // down (square: (x0 + k P, y0 - l P); hex: x0 + (k + (l odd ? 1/2 : 0)) P, y0 - l P sqrt(3)/2).
  double originXMm = 0.0, originYMm = 0.0;
  int cols = 1, rows = 1;     // lenslets with indices (reported; -1 for the others)
  // The sheet is cut larger than the indexed lenslets: the lattice continues for this many
  // lenslets on every side, and the plate's side is at the edge of that (so the outermost
  // indexed lenslets behave like inner ones).
  int marginCells = 4;
  double gapMm = 3.3;         // the panel's emitting plane is z = -gap
  double referenceIndex = 0.0;  // n placing the reference plane; <= 0: n(587.56 nm)
};

struct RealMlaOptions {
  FresnelMode fresnel = FresnelMode::Stochastic;
  double absorptionPerMm = 0.0;  // Beer-Lambert alpha, 1/mm (0: clear)
  int maxEvents = 32;            // surface interactions before a ray is given up
};

// Where and how a ray left the MLA (display frame).
struct MlaExit {
  Point3d p{0.0};         // the last surface point (or the origin when the ray missed the MLA)
  Vec3d d{0.0};           // unit direction leaving the MLA
  double throughput = 1;  // Fresnel (Weighted mode) x absorption
  int capK = -1, capL = -1;      // cap the ray last refracted through (-1: none, or in the margin)
  int entryK = -1, entryL = -1;  // cell where the ray first met the MLA (-1: missed)
  int events = 0;         // surface interactions
  int reflections = 0;    // Fresnel reflections (Stochastic mode)
  int tir = 0;            // total internal reflections
  double glassPathMm = 0; // path length inside the material
};

// Every surface interaction of one trace (for tests and diagnostics).
struct MlaTraceEvent {
  enum class Surface { Cap, Land, Wall, Flat };
  enum class Action { Refract, Reflect, Tir };
  Surface surface = Surface::Cap;
  Action action = Action::Refract;
  int k = -1, l = -1;     // lattice cell of the hit (may lie outside 0..cols-1 / 0..rows-1)
  Point3d p{0.0};         // hit point, display frame
  Vec3d dIn{0.0}, dOut{0.0};  // unit directions before and after
  Vec3d normal{0.0};      // unit surface normal at p, pointing out of the material
  double nIn = 1, nOut = 1;   // indices on the incident and the outgoing side
  double reflectance = 0; // unpolarised Fresnel R at this interface (1 for TIR)
};
struct MlaTraceLog {
  std::vector<MlaTraceEvent> events;
};

class RealMla final : public MlaModel {
 public:
  // Throws InputError when the cap does not cover the aperture ((1 + kappa) r^2 >= R^2), the
  // caps do not fit in the substrate (T <= s_max), the panel would lie inside or above the
  // MLA, or a number is out of range. `file` names the description in messages.
  RealMla(const RealMlaGeometry& g, IorPtr ior, const RealMlaOptions& o = {}, const std::string& file = "");

  // The display's MLA on the layout's physical lens centres (lensX, lensY: EI (k, l) sits
  // behind lenslet (k, l)), panel at z = -gapMm. Material from display.mla (PMMA if empty),
  // R from radius_of_curvature_mm or (n_d - 1) f.
  static std::unique_ptr<RealMla> fromDisplay(const Display& display, const EiLayout& layout, double gapMm,
                                              const RealMlaOptions& o = {});
  static RealMlaGeometry geometryFor(const Display& display, const EiLayout& layout, double gapMm);

  // MlaModel (backward: viewer -> panel); fresnelMode() is options().fresnel.
  using MlaModel::traceToPanel;
  bool traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng, PanelArrival& out) const override;
  FresnelMode fresnelMode() const override { return opt_.fresnel; }
  bool isDispersive() const override { return ior_->isDispersive(); }
  float frontZ() const override { return frontZf_; }  // rounded up: a ray from there starts in air
  // Any cell of the (unbounded) lattice. cellDepth: where the caps meet at the middle of a cell
  // edge; cellBorderDepth: where they meet along the edge (lower toward the corners).
  bool lensletCell(double x, double y, LensletCell& out) const override;
  double cellDepth() const override;
  double cellBorderDepth(const LensletCell& cell, int e, double x, double y) const override;

  // General trace in double precision: `o` (in air, or inside the material) and unit `d`,
  // until the ray leaves the MLA for good (true: `out` holds where and which way) or is lost
  // (absorbed at the plate's side, or more than maxEvents interactions: false). `rng` may be
  // null only for the Weighted and Off modes.
  bool trace(const Point3d& o, const Vec3d& d, double lambdaNm, FresnelMode mode, Rng* rng, MlaExit& out,
             MlaTraceLog* log = nullptr) const;
  // Forward: from a panel point toward the viewer (d.z > 0). True when the ray leaves the MLA
  // heading toward the viewer. Without `rng` Fresnel is Weighted, else options().fresnel.
  bool traceToViewer(const Point3d& o, const Vec3d& d, double lambdaNm, Rng* rng, MlaExit& out,
                     MlaTraceLog* log = nullptr) const;

  // Geometry.
  const RealMlaGeometry& geometry() const { return g_; }
  const RealMlaOptions& options() const { return opt_; }
  double n(double lambdaNm) const;             // index of the material
  double referenceIndex() const { return nRef_; }
  double panelZ() const { return -g_.gapMm; }
  double vertexZ() const { return zv_; }       // z of the cap vertices
  double flatZ() const;                        // z of the flat face
  double backZ() const { return backZ_; }      // lowest z of the MLA
  double frontNodalZ() const { return 0.0; }   // H = N (panel side): the reference plane
  double rearNodalZ() const;                   // H' = N' = T (n_ref - 1) / n_ref
  double maxSagMm() const { return sMax_; }    // s_max: cap depth at A's farthest point
  double capSag(double r) const;               // sag at radius r from a lenslet's axis
  double apertureRadiusMm() const { return rMax_; }  // A's farthest point from the centre
  bool hasLand() const { return hasLand_; }
  // Points on the boundary of a lenslet's clear aperture A (cell-local x, y): the polygon's
  // vertices and edge midpoints, or 32 points on the circle.
  std::vector<std::array<double, 2>> apertureOutline() const;
  // True when the cell-local point (lx, ly) is inside the lenslet's clear aperture A (the
  // aperture shape clipped to the lattice cell).
  bool inClearAperture(double lx, double ly) const;
  // z of the cap surface at cell-local (lx, ly) (meaningful inside A).
  double capZ(double lx, double ly) const { return zv_ - s_ * capSag(std::sqrt(lx * lx + ly * ly)); }
  // Paraxial thick-lens quantities at a wavelength (plano-convex, vertex radius R):
  double focalLength(double lambdaNm) const;   // f = R / (n - 1)
  // Paraxial focal points (thick-lens formulas, z in the display frame). Collimated light from
  // the viewer focuses at frontFocalZ: the panel-side surface is then the flat face at
  // distance BFL = f - T/n (curved-toward-viewer) or the vertex at distance f (toward panel).
  // Collimated light from the panel focuses at rearFocalZ: f beyond the vertex
  // (curved-toward-viewer) or f - T/n beyond the flat face (curved-toward-panel).
  // At n = n_ref, frontFocalZ = -f (H on z = 0) and rearFocalZ = rearNodalZ() + f.
  double frontFocalZ(double lambdaNm) const;
  double rearFocalZ(double lambdaNm) const;
  // Lenslet (k, l)'s axis point on z = 0 (any k, l, also outside the array).
  Point3d lensletCentre(int k, int l) const;
  // The lattice cell holding (x, y) (nearest centre; indices may be out of range).
  void cellAt(double x, double y, int& k, int& l) const;
  bool inRange(int k, int l) const { return k >= 0 && l >= 0 && k < g_.cols && l < g_.rows; }
  // True when p (display frame) is inside the material.
  bool insideMaterial(const Point3d& p) const;

 private:
  // Internally rays live in a canonical frame (x, y, u): u is the depth into the material
  // below the vertex plane (u = s (z_v - z)), so both orientations share one code path.
  struct Hit;
  struct Edge {
    double nx, ny, h;  // half-plane nx x + ny y <= h (local coordinates of a cell)
  };
  // canonical frame <-> display frame
  Vec3d toC(const Vec3d& p) const { return {p.x, p.y, s_ * (zv_ - p.z)}; }
  Vec3d dirC(const Vec3d& d) const { return {d.x, d.y, -s_ * d.z}; }
  Vec3d fromC(const Vec3d& q) const { return {q.x, q.y, zv_ - s_ * q.z}; }

  // Construction steps (after validation and the index table), in this order.
  void buildCellAndAperture();
  void buildOutline();
  void placeSurfaces(const std::string& file);
  void placeExtent(const std::string& file);

  void centreOf(int k, int l, double& cx, double& cy) const;
  bool insideAperture(double lx, double ly, double tol) const;
  int nextHit(const Vec3d& o, const Vec3d& d, bool inGlass, Hit& h) const;  // 0 escape, 1 hit, 2 lost
  bool structuredHit(const Vec3d& o, const Vec3d& d, double t0, double t1, bool entering, Hit& h) const;
  bool cellHit(const Vec3d& o, const Vec3d& d, int k, int l, double t0, double t1, bool entering, Hit& h) const;
  bool boxInterval(const Vec3d& o, const Vec3d& d, double& t0, double& t1) const;
  bool insideC(const Vec3d& q) const;

  RealMlaGeometry g_;
  RealMlaOptions opt_;
  IorPtr ior_;
  std::vector<float> nTable_;  // n at 300 + i nm
  double nRef_ = 1.5;
  double s_ = 1.0;             // +1 curved toward viewer, -1 toward panel
  double zv_ = 0.0;            // vertex plane z
  double frontZ_ = 0.0, backZ_ = 0.0;
  float frontZf_ = 0.0f;
  double R_ = 1.0, K1_ = 1.0;  // vertex radius, 1 + conic
  double sMax_ = 0.0, rMax_ = 0.0;
  double rowH_ = 1.0;          // row spacing (P or P sqrt(3)/2)
  bool hex_ = false, hasLand_ = false, circle_ = false;
  double apR2_ = 0.0;          // circle aperture radius^2
  std::array<Edge, 6> cellEdges_{};
  int nCellEdges_ = 4;
  std::array<Edge, 6> apEdges_{};  // aperture edges not on the cell boundary (walls)
  int nApEdges_ = 0;
  std::vector<std::array<double, 2>> outline_;
  double boxX0_ = 0, boxX1_ = 0, boxY0_ = 0, boxY1_ = 0;
  int maxSteps_ = 16;          // cells a walk may cross
};

// The factory the view simulation uses: RealMla::fromDisplay with default options
// (Stochastic Fresnel, no absorption).
std::unique_ptr<MlaModel> makeRealMla(const Display& display, const EiLayout& layout, double gapMm);

}  // namespace inim
