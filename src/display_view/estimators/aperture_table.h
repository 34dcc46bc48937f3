#pragma once
// The camera aperture as a quadrature rule (the Quadrature estimator's table, one per block of
// pixels; docs/view-estimators.md).
//
// For one pixel position: the camera weight (CameraModel::apertureRay) on a G x G grid of cells
// over the aperture domain (CameraModel::apertureDomain). Each cell whose 4 corners pass gets
// the trapezoid mean of their weights x the cell area, at the cell centre; each cell whose
// corners disagree (the pupil's edge, vignetting) is refined by 4 x 4 midpoint sub-samples
// (weight = their mean x area, at the centroid of the passing ones); cells with no passing
// corner are dropped. `total`, the sum of the weights, is the integral of the camera weight over
// the aperture (tests/display_view/test_aperture_table.cpp checks it against Monte Carlo).
//
// Each point also carries its ray's offsets from the centre ray (through the weighted centroid
// `centre`, same pixel position and wavelength) where the rays cross the plane z = planeZ: the
// crossing point (dhx, dhy, mm) and the slope (dsx, dsy: d.x / -d.z, d.y / -d.z). The estimator
// maps these offsets through the MLA's local Jacobians to panel offsets, so the camera lens's own
// non-linearity (pupil aberrations, the focus spot) is kept for the table's pixel and only the
// MLA is linearised.
#include <cstdint>
#include <vector>

#include "camera/camera_model.h"
#include "core/geometry.h"

namespace inim {

struct ApertureTable {
  struct Point {
    float ax, ay;    // offset from `centre` (aperture coordinates)
    float w;         // weight (camera weight x area)
    float dhx, dhy;  // crossing point - the centre ray's, on z = planeZ (mm)
    float dsx, dsy;  // slope - the centre ray's
  };
  std::vector<Point> points;
  Vec2d centre{0.0};                // weighted centroid of the aperture
  double total = 0.0;               // sum of the weights
  double rmsH = 0.0, rmsS = 0.0;    // weighted rms of |dh| and |ds|
  double cellW = 0.0, cellH = 0.0;  // grid cell size (aperture coordinates)
  float centreWeight = 0.0f;        // apertureRay's weight at the centre (0: the centre is blocked)
  bool valid() const { return total > 0.0 && centreWeight > 0.0f && !points.empty(); }
};

// `rays` is incremented by the number of camera rays traced. The table is invalid (empty) when
// a ray of the aperture does not head down through z = planeZ.
ApertureTable buildApertureTable(const CameraModel& camera, Vec2 pixel, float lambdaNm, int grid, uint64_t& rays,
                                 float planeZ = 0.0f);

// The table's `total` alone (no crossings): the integral of the camera weight over the aperture,
// i.e. the mean weight of CameraModel::generateRay over uLens at this pixel position and
// wavelength; 0 when no ray passes.
double apertureWeightIntegral(const CameraModel& camera, Vec2 pixel, float lambdaNm, int grid, uint64_t& rays);

}  // namespace inim
