#pragma once
// Chief rays traced through an optical stack (docs/formats.md §3.6a, `--chief-rays traced`):
// each panel pixel's display ray is the real ray from the pixel's centre that passes through
// the centre of its lenslet's aperture stop, traced through every layer at one wavelength
// (refraction with n(lambda); Fresnel off; a ray that TIR sends back or a sheet or wall absorbs
// is no chief ray). The pinhole model's ray (rays/pinhole_rays.h) is its first-order limit: a
// straight line from the pixel through the lenslet's principal point.
//
// The stop is found to first order (findApertureStop, display/stack_first_order.h). The ray through it is solved by Newton's method on the two
// launch slopes, the stop crossing of the real ray through the layers below the stop matched to
// the lenslet's axis within 1e-10 mm.
//
// Whole layouts: when every lattice layer shares one lattice and pitch, every lenslet is the
// same, so a pixel's chief ray depends only on its offset from its lenslet's centre; the rays
// are solved on a grid of offsets (tableStepMm) and interpolated bilinearly, like
// real_lens_rays.h. Pixels next to a grid entry without a chief ray are solved directly.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/geometry.h"
#include "display/ei_layout.h"
#include "display/optical_stack.h"
#include "display/stack_first_order.h"
#include "rays/ray_set.h"

namespace inim {

class ProgressBar;
class StackTracer;

struct TracedChiefRayOptions {
  double wavelengthNm = kLambdaDNm;
  double tableStepMm = 0.02;  // 0: every pixel solved directly
  // A curved stack's pinhole model: each pixel's ray through its lenslet's principal point, from
  // the panel as built (`--chief-rays pinhole` on a curved display); no ray is traced.
  bool pinholeOnly = false;
};

struct TracedChiefRayStats {
  uint64_t rays = 0;
  uint64_t fallback = 0;    // no chief ray: the pinhole ray used
  uint64_t crosstalk = 0;   // left through another lenslet than the pixel's own
  double maxDeviationDeg = 0.0, meanDeviationDeg = 0.0;  // angle to the pinhole ray
  double seconds = 0.0;
  std::string stop;         // which aperture is the stop
};

// One pixel's chief ray through a stack whose lattices are placed relative to (originX, originY)
// (StackTracer's frame: the panel at z = 0).
class StackChiefRaySolver {
 public:
  StackChiefRaySolver(const OpticalStack& stack, double originXMm, double originYMm, double wavelengthNm);
  ~StackChiefRaySolver();

  // The chief ray from panel point (px, py) (a curved panel's arc coordinates) through the stop
  // of the lenslet whose axis is at lattice point (cx, cy): where it leaves the stack and which
  // way (the stack's frame, the panel's vertex at z = 0); false when there is none.
  bool solve(double px, double py, double cx, double cy, Point3d& exitP, Vec3d& exitD, bool* crosstalk = nullptr) const;
  // The pinhole model's ray of a curved stack: from the panel point toward lenslet (cx, cy)'s
  // principal point H (its axis at the stack's first-order H); flat stacks: toward (cx, cy, H).
  Vec3d pinholeDirection(double px, double py, double cx, double cy) const;
  Point3d panelPoint(double px, double py) const { return panel_.toWorld(px, py, 0.0); }
  bool curved() const { return !array_.flat(); }
  const ApertureStop& stop() const { return stop_; }
  double pitchMm() const { return pitchMm_; }

 private:
  bool stopMiss(double px, double py, double tx, double ty, double cx, double cy, double& mx, double& my) const;
  // Curved stacks: the launch direction is the lenslet's axis tilted by (tx, ty) along e1, e2.
  struct Aim {
    Point3d p0;
    Vec3d axis, e1, e2;
    double cx = 0, cy = 0;
    Vec3d dir(double tx, double ty) const { return glm::normalize(axis + tx * e1 + ty * e2); }
  };
  bool curvedMiss(const Aim& a, double tx, double ty, double& mx, double& my) const;
  bool solveCurved(double px, double py, double cx, double cy, Point3d& exitP, Vec3d& exitD, bool* crosstalk) const;

  ApertureStop stop_;
  std::unique_ptr<StackTracer> below_;  // the layers below the stop's plane (null: none)
  std::unique_ptr<StackTracer> whole_;
  double panelIndex_ = 1.0, wavelengthNm_ = kLambdaDNm, pitchMm_ = 1.0;
  double stopOffsetX_ = 0.0, stopOffsetY_ = 0.0;  // the stop layer's lattice offset
  CurvedFrame array_, panel_;
  double principalZ_ = 0.0;  // H, from the panel
};

// All rays of the layout in ray order, like generatePinholeRays, in the display frame: the panel
// at z = -panelDepthMm, each ray's origin moved along it to z = 0. `stack` is the display's as
// built, the panel at its z = 0; its lattices are placed on the layout's lenslet (0, 0). The
// layout says which pixels belong to which lenslet; its own gap (the pinhole model's generation
// gap) plays no part. InputError when the stack has no stop. Deterministic; parallel.
RaySet generateTracedChiefRays(const EiLayout& L, const OpticalStack& stack, double panelDepthMm,
                               const TracedChiefRayOptions& o, TracedChiefRayStats* stats = nullptr,
                               ProgressBar* progress = nullptr);

// One line for command output.
std::string summaryText(const TracedChiefRayOptions& o, const TracedChiefRayStats& st);

}  // namespace inim
