#pragma once
// Colour corrections fitted by least squares to pairs (source triple -> target triple).
#include <array>
#include <vector>

#include "calibration/colour_model.h"

namespace inim {

// The pairs a model is fitted to; sources[i] should map to targets[i].
struct ColourPairs {
  std::vector<Vec3d> sources, targets;
};

// target = M source. Fitted by linear least squares, or with the constraint that M maps a given
// source white exactly onto a target white (white preservation: neutrals stay neutral, at the
// cost of a slightly larger residual elsewhere).
class MatrixModel : public ColourModel {
 public:
  explicit MatrixModel(const glm::dmat3& matrix = glm::dmat3(1.0)) : matrix_(matrix) {}
  static MatrixModel fit(const ColourPairs& pairs, double ridge = 0.0);
  // Least squares over the matrices with M sourceWhite = targetWhite (solved in the null space
  // of the constraint, so the white is mapped to rounding, not approximately).
  static MatrixModel fitPreservingWhite(const ColourPairs& pairs, const Vec3d& sourceWhite,
                                        const Vec3d& targetWhite, double ridge = 0.0);

  Vec3d apply(const Vec3d& source) const override { return matrix_ * source; }
  std::string name() const override { return "matrix_3x3"; }
  nlohmann::json parameters() const override;
  const glm::dmat3& matrix() const { return matrix_; }  // glm: column-major
  double residualRms() const { return residualRms_; }
  bool preservesWhite() const { return preservesWhite_; }

 private:
  glm::dmat3 matrix_;
  double residualRms_ = 0.0;
  bool preservesWhite_ = false;
};

// Second-order root-polynomial (Finlayson, Mackiewicz & Hurlbert 2015, "Color correction using
// root-polynomial regression"): target = C [r, g, b, sqrt(rg), sqrt(gb), sqrt(rb)]. Every term
// has degree 1, so f(k x) = k f(x) for k > 0 (exposure invariance). A product below zero
// contributes 0 to its root term (this keeps the invariance and continuity).
class RootPolynomialModel : public ColourModel {
 public:
  static constexpr int kTerms = 6;
  using Coefficients = std::array<std::array<double, kTerms>, 3>;  // [output channel][term]

  explicit RootPolynomialModel(const Coefficients& coefficients) : coefficients_(coefficients) {}
  static RootPolynomialModel fit(const ColourPairs& pairs, double ridge = 0.0);
  static std::array<double, kTerms> terms(const Vec3d& source);

  Vec3d apply(const Vec3d& source) const override;
  std::string name() const override { return "root_polynomial_2"; }
  nlohmann::json parameters() const override;
  const Coefficients& coefficients() const { return coefficients_; }
  double residualRms() const { return residualRms_; }

 private:
  Coefficients coefficients_;
  double residualRms_ = 0.0;
};

}  // namespace inim
