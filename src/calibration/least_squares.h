#pragma once
// Linear least squares shared by the colour-correction fits: min |A X - B|^2 + ridge |X|^2,
// solved by Householder QR (no normal equations, so the conditioning is that of A, not A^T A).
#include <cstddef>
#include <vector>

namespace inim {

// A dense row-major matrix of doubles.
struct DenseMatrix {
  size_t rows = 0, cols = 0;
  std::vector<double> values;  // rows * cols, row-major

  DenseMatrix() = default;
  DenseMatrix(size_t rowCount, size_t colCount) : rows(rowCount), cols(colCount), values(rowCount * colCount, 0.0) {}
  double& operator()(size_t r, size_t c) { return values[r * cols + c]; }
  double operator()(size_t r, size_t c) const { return values[r * cols + c]; }
};

struct LeastSquaresSolution {
  DenseMatrix coefficients;  // cols(A) x cols(B)
  // Root mean square over the rows of the Euclidean length of each row's residual A x - b
  // (the data term only, without the ridge term).
  double residualRms = 0.0;
};

// Solves for X minimising |design X - targets|^2 + ridge |X|^2 (ridge >= 0, a Tikhonov term that
// keeps nearly collinear terms bounded; 0 gives the plain least-squares solution).
// Throws InputError (key `pairs`) with fewer rows than unknowns, or when the design is
// rank-deficient and ridge is 0.
LeastSquaresSolution solveLeastSquares(const DenseMatrix& design, const DenseMatrix& targets,
                                       double ridge = 0.0);

}  // namespace inim
