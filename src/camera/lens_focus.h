#pragma once
// Focus (by moving the sensor), aperture control (by scaling the stop) and spot diagrams.
#include "camera/lens_system.h"

namespace inim {

enum class FocusMode {
  Paraxial,  // the paraxial image plane (real near-axis rays, extrapolated)
  BestRms,   // the plane of smallest RMS spot radius of the full-aperture axial bundle
};
const char* focusModeName(FocusMode m);

struct SpotDiagram {
  int rays = 0;                  // rays through every aperture
  double rmsRadiusMm = 0.0;      // about the centroid, at the given sensor distance
  Vec2d centroidMm{0.0};         // on the sensor plane, lens x/y
  double bestShiftMm = 0.0;      // sensor shift (+z toward the image) that minimises the RMS radius
  double bestRmsRadiusMm = 0.0;  // the RMS radius there
};

// Spot of an object point (lens coordinates, in front of the lens) on the plane at
// `sensorDistanceMm` behind the last vertex: rays aimed at a grid x grid square over the
// paraxial entrance pupil (1.3 x its radius; the apertures cut the real beam) at one wavelength.
SpotDiagram spotDiagram(const LensSystem& lens, const Point3d& objectPoint, double sensorDistanceMm,
                        double lambdaNm = kLensReferenceLambdaNm, int grid = 41);
// The same for an object at infinity seen in `direction` (unit, travelling toward +z).
SpotDiagram spotDiagramAtInfinity(const LensSystem& lens, const Vec3d& direction, double sensorDistanceMm,
                                  double lambdaNm = kLensReferenceLambdaNm, int grid = 41);

// Sensor distance behind the last vertex that focuses an axial object point at lens
// z = objectZ (< 0; -infinity for an object at infinity).
double focusSensorDistance(const LensSystem& lens, double objectZ, FocusMode mode = FocusMode::BestRms,
                           double lambdaNm = kLensReferenceLambdaNm);

// Scales the stop so that EFL / EPD = fNumber (paraxial, object at infinity) and returns the
// new stop diameter. Throws InputError (the lens file, key "f_number") when the request is
// faster than the design's stop allows or not > 0.
double setFNumber(LensSystem& lens, double fNumber, double lambdaNm = kLensReferenceLambdaNm);
// The f-number of the design's own stop.
double widestFNumber(const LensSystem& lens, double lambdaNm = kLensReferenceLambdaNm);

}  // namespace inim
