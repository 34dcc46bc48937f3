#include "calibration/least_squares.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/format.h"

namespace inim {
namespace {

// The design with sqrt(ridge) I appended below it, and the targets with zero rows to match:
// the ridge problem as an ordinary least-squares problem.
void appendRidgeRows(DenseMatrix& design, DenseMatrix& targets, double ridge) {
  if (ridge <= 0.0) return;
  const size_t n = design.rows, p = design.cols;
  design.values.resize((n + p) * p, 0.0);
  targets.values.resize((n + p) * targets.cols, 0.0);
  design.rows = targets.rows = n + p;
  for (size_t j = 0; j < p; ++j) design(n + j, j) = std::sqrt(ridge);
}

// Householder QR in place: on return the upper triangle of `a` holds R, and `b` holds Q^T b.
void householderQr(DenseMatrix& a, DenseMatrix& b) {
  for (size_t k = 0; k < a.cols; ++k) {
    double norm = 0.0;
    for (size_t i = k; i < a.rows; ++i) norm += a(i, k) * a(i, k);
    norm = std::sqrt(norm);
    if (norm == 0.0) continue;
    const double alpha = a(k, k) > 0.0 ? -norm : norm;
    std::vector<double> v(a.rows - k);
    for (size_t i = k; i < a.rows; ++i) v[i - k] = a(i, k);
    v[0] -= alpha;
    double vv = 0.0;
    for (double x : v) vv += x * x;
    if (vv == 0.0) continue;
    auto reflect = [&](DenseMatrix& m, size_t firstCol) {
      for (size_t j = firstCol; j < m.cols; ++j) {
        double dot = 0.0;
        for (size_t i = k; i < m.rows; ++i) dot += v[i - k] * m(i, j);
        const double scale = 2.0 * dot / vv;
        for (size_t i = k; i < m.rows; ++i) m(i, j) -= scale * v[i - k];
      }
    };
    reflect(a, k);
    reflect(b, 0);
  }
}

DenseMatrix backSubstitute(const DenseMatrix& r, const DenseMatrix& qtb) {
  const size_t p = r.cols;
  double largest = 0.0;
  for (size_t j = 0; j < p; ++j) largest = std::max(largest, std::abs(r(j, j)));
  DenseMatrix x(p, qtb.cols);
  for (size_t j = p; j-- > 0;) {
    if (!(std::abs(r(j, j)) > 1e-13 * largest))
      throw InputError("", "pairs", "column " + std::to_string(j) + " of the design",
                       "linearly independent terms (add varied pairs or a ridge term)");
    for (size_t c = 0; c < qtb.cols; ++c) {
      double sum = qtb(j, c);
      for (size_t k = j + 1; k < p; ++k) sum -= r(j, k) * x(k, c);
      x(j, c) = sum / r(j, j);
    }
  }
  return x;
}

double residualRms(const DenseMatrix& design, const DenseMatrix& targets, const DenseMatrix& x) {
  if (design.rows == 0) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < design.rows; ++i)
    for (size_t c = 0; c < targets.cols; ++c) {
      double fitted = 0.0;
      for (size_t j = 0; j < design.cols; ++j) fitted += design(i, j) * x(j, c);
      sum += (fitted - targets(i, c)) * (fitted - targets(i, c));
    }
  return std::sqrt(sum / double(design.rows));
}

}  // namespace

LeastSquaresSolution solveLeastSquares(const DenseMatrix& design, const DenseMatrix& targets, double ridge) {
  if (targets.rows != design.rows)
    throw InputError("", "pairs", std::to_string(targets.rows) + " targets for " + std::to_string(design.rows) + " sources",
                     "one target per source");
  if (!(ridge >= 0.0) || !std::isfinite(ridge))
    throw InputError("", "ridge", formatNumber(ridge), "a finite value >= 0");
  if (ridge == 0.0 && design.rows < design.cols)
    throw InputError("", "pairs", std::to_string(design.rows),
                     "at least " + std::to_string(design.cols) + " pairs (one per unknown of the model)");
  DenseMatrix a = design, b = targets;
  appendRidgeRows(a, b, ridge);
  householderQr(a, b);
  LeastSquaresSolution out;
  out.coefficients = backSubstitute(a, b);
  out.residualRms = residualRms(design, targets, out.coefficients);
  return out;
}

}  // namespace inim
