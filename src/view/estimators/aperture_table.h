#pragma once
// The camera aperture as a quadrature rule, for the Aperture panel estimator (view_renderer.h).
//
// ApertureSpace: 2-D coordinates `a` on the camera's aperture in which the camera's ray
// generation is a fixed function of (pixel, a, wavelength):
//   - real lens: a = (x, y) on the rear-vertex plane (lens coordinates, mm), the points that
//     RealLensCameraModel samples through its exit-pupil bounds; ray(pixel, a) =
//     traceFromSensor(sensor point, a) / (z^2 E0) (irradiance per unit radiance per mm^2 of the
//     rear plane, normalised like generateRay), so the integral of ray()'s weight over a equals
//     the expectation of generateRay's weight over its lens sample square;
//   - thin lens: a = the lens-plane point in units of the aperture radius (the unit disk; the
//     lens sample is its inverse concentric map), weight = generateRay's / pi;
//   - pinhole (or any other camera): a = the lens sample itself in [0, 1)^2, ray() =
//     generateRay() (the pinhole ignores it: the affine map's Jacobian is 0).
// ApertureKernel: for one pixel position, the aperture's weighted shape on a G x G grid of
// cells over its domain (the exit-pupil box of the pixel's radius, rotated as the camera
// rotates it, grown by 5%): each cell whose 4 corners pass gets the trapezoid mean of their
// weights x the cell area, at the cell centre; each cell whose corners disagree (the pupil's
// edge, vignetting) is refined by 4 x 4 midpoint sub-samples (weight = their mean x area, at
// the centroid of the passing ones); cells with no passing corner are dropped. The points are
// stored relative to the weighted centroid `centre`. `total` = the sum of the weights, the
// integral of the camera weight over the aperture (tests check it against Monte Carlo).
#include <cstdint>
#include <vector>

#include "camera/camera_model.h"
#include "core/geometry.h"

namespace inim {

class ApertureSpace {
 public:
  explicit ApertureSpace(const CameraModel& camera);
  // The domain of `a` worth scanning for a pixel position; false when no ray can pass.
  bool domain(Vec2 pixel, Vec2d& lo, Vec2d& hi) const;
  // The camera ray for a pixel position and aperture point at a wavelength, with its weight
  // per unit area of `a` (0: blocked).
  float ray(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const;
  bool isRealLens() const { return real_ != nullptr; }

 private:
  const CameraModel& camera_;
  const RealLensCameraModel* real_ = nullptr;
  bool thin_ = false;    // thin lens: a = lens-plane point / aperture radius (unit disk)
  double zScale_ = 1.0;  // 1 / (z^2 E0) for the real lens
};

// Each point also carries its camera ray's offsets from the centre ray (at the same pixel
// position and wavelength) where the rays cross the plane z = planeZ: the crossing point
// (dhx, dhy, mm) and the slope (dsx, dsy: d.x / -d.z, d.y / -d.z). The renderer maps these
// bundle offsets through the MLA's local Jacobians (per pixel and lenslet) to panel offsets, so
// the camera lens's own non-linearity (pupil aberrations, the focus spot) is kept exactly for
// the table's pixel and only the MLA is linearised. shiftH / shiftS: least-squares affine fit
// of the offsets against the aperture coordinates (per unit of a), to move the whole kernel by
// a sub-cell shift.
struct ApertureKernel {
  struct Point {
    float ax, ay;    // offset from `centre` (aperture coordinates)
    float w;         // weight (camera weight x area)
    float dhx, dhy;  // crossing point - the centre ray's, on z = planeZ (mm)
    float dsx, dsy;  // slope - the centre ray's
  };
  double shiftH[2][2] = {}, shiftS[2][2] = {};
  double rmsH = 0.0, rmsS = 0.0;  // weighted rms of |dh| and |ds|
  std::vector<Point> points;
  Vec2d centre{0.0};      // weighted centroid of the aperture
  double total = 0.0;     // sum of the weights
  double rmsRadius = 0.0; // sqrt(weighted mean |a - centre|^2)
  double cellW = 0.0, cellH = 0.0;  // grid cell size (aperture coordinates)
  float centreWeight = 0.0f;        // ray() weight at the centre (0: the centre is blocked)
  bool valid() const { return total > 0.0 && centreWeight > 0.0f && !points.empty(); }
};

// `rays` is incremented by the number of camera rays traced. The kernel is invalid (empty) when
// a ray of the aperture does not head down through z = planeZ.
ApertureKernel buildApertureKernel(const ApertureSpace& space, Vec2 pixel, float lambdaNm, int grid, uint64_t& rays,
                                   float planeZ = 0.0f);

}  // namespace inim
