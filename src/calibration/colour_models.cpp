#include "calibration/colour_models.h"

#include <cmath>
#include <string>

#include "calibration/least_squares.h"
#include "core/error.h"

namespace inim {
namespace {

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkPairs(const ColourPairs& pairs) {
  if (pairs.sources.size() != pairs.targets.size())
    throw InputError("", "pairs",
                     std::to_string(pairs.sources.size()) + " sources, " + std::to_string(pairs.targets.size()) + " targets",
                     "as many targets as sources");
  for (size_t i = 0; i < pairs.sources.size(); ++i)
    if (!finite(pairs.sources[i]) || !finite(pairs.targets[i]))
      throw InputError("", "pairs", "pair " + std::to_string(i), "finite source and target values");
}

DenseMatrix targetRows(const std::vector<Vec3d>& targets) {
  DenseMatrix b(targets.size(), 3);
  for (size_t i = 0; i < targets.size(); ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = targets[i][c];
  return b;
}

nlohmann::json rows(const glm::dmat3& m) {
  nlohmann::json out = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) out.push_back({m[0][r], m[1][r], m[2][r]});
  return out;
}

// Two unit vectors orthogonal to w and to each other: a basis of the matrices' rows that
// leave M w unchanged.
std::array<Vec3d, 2> orthogonalBasis(const Vec3d& w) {
  const Vec3d u = glm::normalize(w);
  const Vec3d a = std::abs(u.x) < 0.6 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  const Vec3d n1 = glm::normalize(glm::cross(u, a));
  return {n1, glm::cross(u, n1)};
}

}  // namespace

MatrixModel MatrixModel::fit(const ColourPairs& pairs, double ridge) {
  checkPairs(pairs);
  DenseMatrix a(pairs.sources.size(), 3);
  for (size_t i = 0; i < pairs.sources.size(); ++i)
    for (int c = 0; c < 3; ++c) a(i, c) = pairs.sources[i][c];
  const LeastSquaresSolution s = solveLeastSquares(a, targetRows(pairs.targets), ridge);
  glm::dmat3 m(0.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[c][r] = s.coefficients(c, r);  // row r of M = column r of X
  MatrixModel out(m);
  out.residualRms_ = s.residualRms;
  return out;
}

// Each row m of M satisfies m . w = t (t the row's target white component): m = t w / |w|^2 + N c
// with N = [n1 n2] orthogonal to w. The free coefficients c solve an ordinary least-squares
// problem with design S N and targets T - (S w) t^T / |w|^2, for all three rows at once.
MatrixModel MatrixModel::fitPreservingWhite(const ColourPairs& pairs, const Vec3d& sourceWhite,
                                            const Vec3d& targetWhite, double ridge) {
  checkPairs(pairs);
  if (!finite(sourceWhite) || glm::dot(sourceWhite, sourceWhite) == 0.0 || !finite(targetWhite))
    throw InputError("", "white", "source or target white", "finite whites, the source white non-zero");
  const std::array<Vec3d, 2> basis = orthogonalBasis(sourceWhite);
  const double w2 = glm::dot(sourceWhite, sourceWhite);
  const size_t n = pairs.sources.size();
  DenseMatrix a(n, 2), b = targetRows(pairs.targets);
  for (size_t i = 0; i < n; ++i) {
    const Vec3d& s = pairs.sources[i];
    a(i, 0) = glm::dot(s, basis[0]);
    a(i, 1) = glm::dot(s, basis[1]);
    for (int c = 0; c < 3; ++c) b(i, c) -= glm::dot(s, sourceWhite) * targetWhite[c] / w2;
  }
  const LeastSquaresSolution sol = solveLeastSquares(a, b, ridge);
  glm::dmat3 m(0.0);
  for (int r = 0; r < 3; ++r) {
    const Vec3d row = targetWhite[r] / w2 * sourceWhite + sol.coefficients(0, r) * basis[0] +
                      sol.coefficients(1, r) * basis[1];
    for (int c = 0; c < 3; ++c) m[c][r] = row[c];
  }
  MatrixModel out(m);
  out.residualRms_ = sol.residualRms;  // the offset moved to the targets: same residual as M's
  out.preservesWhite_ = true;
  return out;
}

nlohmann::json MatrixModel::parameters() const {
  return {{"model", name()}, {"matrix_rows", rows(matrix_)}, {"white_preserving", preservesWhite_},
          {"fit_residual_rms", residualRms_}};
}

std::array<double, RootPolynomialModel::kTerms> RootPolynomialModel::terms(const Vec3d& x) {
  auto root = [](double product) { return product > 0.0 ? std::sqrt(product) : 0.0; };
  return {x.x, x.y, x.z, root(x.x * x.y), root(x.y * x.z), root(x.x * x.z)};
}

RootPolynomialModel RootPolynomialModel::fit(const ColourPairs& pairs, double ridge) {
  checkPairs(pairs);
  DenseMatrix a(pairs.sources.size(), kTerms);
  for (size_t i = 0; i < pairs.sources.size(); ++i) {
    const auto t = terms(pairs.sources[i]);
    for (int j = 0; j < kTerms; ++j) a(i, j) = t[j];
  }
  const LeastSquaresSolution s = solveLeastSquares(a, targetRows(pairs.targets), ridge);
  Coefficients c{};
  for (int channel = 0; channel < 3; ++channel)
    for (int j = 0; j < kTerms; ++j) c[channel][j] = s.coefficients(j, channel);
  RootPolynomialModel out(c);
  out.residualRms_ = s.residualRms;
  return out;
}

Vec3d RootPolynomialModel::apply(const Vec3d& source) const {
  const auto t = terms(source);
  Vec3d out(0.0);
  for (int channel = 0; channel < 3; ++channel)
    for (int j = 0; j < kTerms; ++j) out[channel] += coefficients_[channel][j] * t[j];
  return out;
}

nlohmann::json RootPolynomialModel::parameters() const {
  nlohmann::json coefficientRows = nlohmann::json::array();
  for (const auto& row : coefficients_) coefficientRows.push_back(row);
  return {{"model", name()},
          {"terms", {"r", "g", "b", "sqrt(r*g)", "sqrt(g*b)", "sqrt(r*b)"}},
          {"coefficients", coefficientRows},
          {"fit_residual_rms", residualRms_}};
}

}  // namespace inim
