#pragma once
// The camera as an affine map over a block of pixels (the Quadrature estimator's, one per
// aperture-table block of ~0.1 mm of the sensor): the centre ray (through the aperture table's
// centroid) at the block's centre pixel, its crossing of the MLA's front plane and its slope,
// and their Jacobians with respect to the pixel position (central differences of +-0.5 px,
// one-sided where a probe is blocked). Pixel strata map to the MLA through it, and the lenslet
// borders back to the sensor; over a block the camera's mapping is affine to far below a pixel.
#include <cstdint>
#include <vector>

#include "camera/camera_model.h"
#include "core/geometry.h"
#include "display_view/estimators/aperture_table.h"

namespace inim {

struct BlockCamera {
  bool ok = false;
  Vec2d pixelCentre{0.0};
  Vec2d crossing{0.0}, slope{0.0};  // the centre ray on the front plane; slope = (d.x, d.y) / -d.z
  double dCrossing[2][2] = {}, dSlope[2][2] = {};  // per pixel (row-major: [component][pixel axis])
  double weight = 0.0, dWeight[2] = {0.0, 0.0};   // the centre ray's camera weight and its gradient
  // A dispersive camera: the centre ray's crossing and slope at each wavelength of the list
  // given to buildBlockCamera, minus the reference wavelength's (lateral colour, constant over
  // a block).
  std::vector<Vec2d> colourCrossing, colourSlope;

  // The centre ray at pixel position p (affine in p) at wavelength index i (-1: reference).
  void at(const Vec2d& p, int i, Vec2d& crossingOut, Vec2d& slopeOut, double& weightOut) const {
    const Vec2d d = p - pixelCentre;
    crossingOut = crossing + Vec2d(dCrossing[0][0] * d.x + dCrossing[0][1] * d.y,
                                   dCrossing[1][0] * d.x + dCrossing[1][1] * d.y);
    slopeOut = slope + Vec2d(dSlope[0][0] * d.x + dSlope[0][1] * d.y, dSlope[1][0] * d.x + dSlope[1][1] * d.y);
    if (i >= 0 && size_t(i) < colourCrossing.size()) {
      crossingOut += colourCrossing[size_t(i)];
      slopeOut += colourSlope[size_t(i)];
    }
    weightOut = weight + dWeight[0] * d.x + dWeight[1] * d.y;
  }
};

// The block camera at pixel position `centre` through `table`'s centroid, on the plane z = planeZ
// at `lambdaNm`, with the lateral colour at `colourLambdas` when that list is not empty; `rays`
// counts the camera rays traced. Not ok when a probe cannot cross the plane.
BlockCamera buildBlockCamera(const CameraModel& camera, const ApertureTable& table, Vec2 centre, float lambdaNm,
                             float planeZ, const std::vector<float>& colourLambdas, uint64_t& rays);

}  // namespace inim
