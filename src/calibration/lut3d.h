#pragma once
// A 3D lookup table on the unit cube with tetrahedral interpolation, built by sampling a
// function or by inverting one (drive -> measured becomes measured -> drive).
#include <vector>

#include "calibration/colour_model.h"

namespace inim {

class Lut3d : public ColourModel {
 public:
  static constexpr int kDefaultSize = 33;

  // The identity table with `size` nodes per axis (2..256).
  explicit Lut3d(int size = kDefaultSize);
  // f sampled at every node.
  static Lut3d sample(const ColourFunction& f, int size = kDefaultSize);

  int size() const { return size_; }
  // Input coordinate of node index i along an axis: i / (size - 1).
  double nodeCoordinate(int i) const { return double(i) / double(size_ - 1); }
  Vec3d node(int r, int g, int b) const { return {nodeCoordinate(r), nodeCoordinate(g), nodeCoordinate(b)}; }
  const Vec3d& at(int r, int g, int b) const { return values_[index(r, g, b)]; }
  void set(int r, int g, int b, const Vec3d& value) { values_[index(r, g, b)] = value; }
  // The node values with red changing fastest (the .cube order).
  const std::vector<Vec3d>& values() const { return values_; }

  // Tetrahedral interpolation (the cube cell split into six tetrahedra along its diagonal, so
  // any affine function is reproduced exactly). Inputs are clamped to [0,1] first, as
  // OpenColorIO does.
  Vec3d eval(const Vec3d& rgb) const;
  Vec3d apply(const Vec3d& source) const override { return eval(source); }
  std::string name() const override { return "lut3d"; }
  std::string describe() const override {
    return "3D LUT, " + std::to_string(size_) + " nodes per axis, tetrahedral";
  }
  // Size, interpolation and the table (rows r g b, red fastest).
  nlohmann::json parameters() const override;

 private:
  size_t index(int r, int g, int b) const { return size_t(r) + size_t(size_) * (size_t(g) + size_t(size_) * size_t(b)); }
  int size_;
  std::vector<Vec3d> values_;
};

struct InversionSettings {
  int size = Lut3d::kDefaultSize;
  int maxIterations = 50;
  double tolerance = 1e-10;         // |F(x) - t| at which a node's solve stops
  double jacobianStep = 1e-6;       // finite-difference step in drive units
  double reachedTolerance = 1e-6;   // |F(x) - t| above which a target counts as out of range
  int guessSamplesPerAxis = 5;      // grid of F samples for the 3x3 starting guess
  // Where the solutions may lie, per channel. [0, 1]: drives a panel can show, so targets out
  // of reach get the nearest drive on the boundary. A wider range lets the table continue the
  // inverse past the boundary (the user clamps after interpolating), so cells that straddle it
  // interpolate exactly for a smooth F; F must then be defined there too.
  double lowerBound = 0.0, upperBound = 1.0;
};

struct InverseLut {
  Lut3d lut;                        // measured target -> drive in [0,1]^3
  std::vector<double> residuals;    // |F(lut node) - target| per node, in values() order
  double maxResidual = 0.0;
  size_t unreachedCount = 0;        // nodes with residual > reachedTolerance (outside F's range)
};

// For every node target t of [0,1]^3, the drive x in the bounds (default [0,1]^3) with F(x) = t,
// or for targets outside F's range the drive (on the bounds' boundary) closest to it in the
// least-squares sense. Projected damped Gauss-Newton with a finite-difference Jacobian, started from a 3x3
// matrix fitted to map F's samples back to their drives. F should be smooth and monotone-ish
// (a display: more drive, more light); F is called only inside the bounds.
InverseLut invertToLut(const ColourFunction& forward, const InversionSettings& settings = {});

}  // namespace inim
