#pragma once
// Exit-pupil bounds for sampling rays from the sensor through a real lens (pbrt-v4's
// RealisticCamera): for sensor points at distance r from the axis (in `intervals` bins up to
// rMax), the bounding box, on the plane of the rear vertex, of every point that a ray from
// the sensor point can aim at and still pass the whole lens. Sampling the box instead of the
// whole rear element wastes few rays; since the box holds every passing ray, nothing is lost.
//
// Each bin's box is the union, over a few sensor radii in the bin and over the given
// wavelengths, of a grid x grid scan of the square 1.5 x the rear clear radius (pbrt's
// scan window), expanded by 1.5 grid cells: box(r), the aperture's domain
// (CameraModel::apertureDomain). A sensor point off the x axis uses its bin's box
// rotated by the point's polar angle. sample() draws from a tighter shape: that box scanned
// again at the same grid, expanded by 1.5 of the finer cells, or the ellipse inscribed in it
// where every passing cell (its four corners) lies inside that ellipse.
#include <memory>
#include <vector>

#include "camera/lens_system.h"
#include "core/geometry.h"

namespace inim {

struct PupilBox {
  Vec2d lo{0.0}, hi{0.0};
  bool empty = true;
  // Every passing cell of the scan lies in the ellipse inscribed in the box: it is sampled
  // instead (a round pupil: 21 % fewer rays vignetted for nothing).
  bool ellipse = false;
  double area() const { return empty ? 0.0 : (ellipse ? 0.25 * kPiD : 1.0) * (hi.x - lo.x) * (hi.y - lo.y); }
  void extend(const Vec2d& p);
};

class ExitPupilBounds {
 public:
  struct Settings {
    int intervals = 64;    // radial bins between 0 and rMax
    int grid = 48;         // scan resolution of the rear window per bin and radius
    int radialSamples = 6; // sensor radii per bin (both ends included)
    std::vector<double> wavelengthsNm;  // empty: the d line only
  };

  ExitPupilBounds() = default;
  // Scans the lens with its current sensor distance. Parallel (TBB), deterministic.
  ExitPupilBounds(const LensSystem& lens, double rMaxMm, const Settings& settings);

  // The bounds of this lens, sensor distance, rMax and settings, scanned once per process: the
  // cameras of fig11's poses and the budget's rungs share one lens (a scan costs 0.5 s of CPU).
  static std::shared_ptr<const ExitPupilBounds> shared(const LensSystem& lens, double rMaxMm, const Settings& settings);

  // A point on the rear-vertex plane (lens coordinates, z = rearZ()) for the sensor point
  // (x, y), with its pdf per unit area; false when no ray from there passes.
  bool sample(const Vec2d& sensorXY, const Vec2& u, Point3d& rearPoint, double& pdfArea) const;
  const PupilBox& box(double r) const;  // the unrotated box of the bin holding radius r
  double rearZ() const { return rearZ_; }
  double rMax() const { return rMax_; }
  int intervals() const { return int(boxes_.size()); }
  // The scan window: the square [-w, w]^2 with w = 1.5 x the rear clear radius.
  double windowHalfWidth() const { return window_; }

 private:
  size_t binOf(double r) const;  // the bin of sensor radius r (both tables have one per bin)
  PupilBox scanBin(const LensSystem& lens, const std::vector<std::vector<double>>& indices, int bin, int nBins, int nR,
                   int grid, const Vec2d& lo, const Vec2d& hi, std::vector<Vec2d>& passing) const;
  std::vector<PupilBox> boxes_;
  std::vector<PupilBox> sampling_;  // per bin: the box scanned again, or its ellipse (sample())
  double rearZ_ = 0.0, rMax_ = 0.0, window_ = 0.0;
};

}  // namespace inim
