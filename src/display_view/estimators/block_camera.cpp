#include "display_view/estimators/block_camera.h"

#include <cmath>

namespace inim {

namespace {

// The ray through the table's centroid at a pixel position: its crossing of z = planeZ and its
// slope there (and its weight); false when blocked or not heading down through the plane.
bool centreCrossing(const CameraModel& camera, const ApertureTable& table, Vec2 pixel, float lambda, float planeZ,
                    Vec2d& crossing, Vec2d& slope, uint64_t& rays, double* weight = nullptr) {
  Ray r;
  ++rays;
  const float w = camera.apertureRay(pixel, table.centre, lambda, r);
  if (weight) *weight = w;
  if (!(w > 0.0f) || !(r.d.z < 0.0f) || !(r.o.z > planeZ)) return false;
  const double t = (double(planeZ) - r.o.z) / r.d.z;
  crossing = Vec2d(r.o.x + t * r.d.x, r.o.y + t * r.d.y);
  slope = Vec2d(r.d.x / -double(r.d.z), r.d.y / -double(r.d.z));
  return std::isfinite(crossing.x) && std::isfinite(crossing.y);
}

}  // namespace

BlockCamera buildBlockCamera(const CameraModel& camera, const ApertureTable& table, Vec2 centre, float lambdaNm,
                             float planeZ, const std::vector<float>& colourLambdas, uint64_t& rays) {
  BlockCamera b;
  b.pixelCentre = Vec2d(centre);
  if (!centreCrossing(camera, table, centre, lambdaNm, planeZ, b.crossing, b.slope, rays, &b.weight)) return b;
  for (int axis = 0; axis < 2; ++axis) {
    const Vec2 e = axis == 0 ? Vec2(0.5f, 0.0f) : Vec2(0.0f, 0.5f);
    Vec2d crossingP, slopeP, crossingM, slopeM;
    double weightP, weightM;
    const bool okP = centreCrossing(camera, table, centre + e, lambdaNm, planeZ, crossingP, slopeP, rays, &weightP);
    const bool okM = centreCrossing(camera, table, centre - e, lambdaNm, planeZ, crossingM, slopeM, rays, &weightM);
    double step = 1.0;
    if (!okP && !okM) return b;
    if (!okP) crossingP = b.crossing, slopeP = b.slope, weightP = b.weight, step = 0.5;
    if (!okM) crossingM = b.crossing, slopeM = b.slope, weightM = b.weight, step = 0.5;
    for (int i = 0; i < 2; ++i) {
      b.dCrossing[i][axis] = (crossingP[i] - crossingM[i]) / step;
      b.dSlope[i][axis] = (slopeP[i] - slopeM[i]) / step;
    }
    b.dWeight[axis] = (weightP - weightM) / step;
  }
  for (float lambda : colourLambdas) {
    Vec2d crossing, slope;
    if (!centreCrossing(camera, table, centre, lambda, planeZ, crossing, slope, rays)) return b;
    b.colourCrossing.push_back(crossing - b.crossing);
    b.colourSlope.push_back(slope - b.slope);
  }
  b.ok = true;
  return b;
}

}  // namespace inim
