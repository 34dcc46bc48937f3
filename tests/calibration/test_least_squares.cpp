// Householder-QR least squares with a ridge term.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/least_squares.h"
#include "calibration/test_functions.h"
#include "expect_input_error.h"

namespace inim {
namespace {

// Data made by a known X (no noise) give X back to rounding and a zero residual.
TEST(LeastSquares, ExactDataGiveTheGeneratingCoefficients) {
  const auto rows = testing::pseudoRandomColours(12, -1.0, 1.0);
  DenseMatrix a(rows.size(), 4), b(rows.size(), 2);
  const double x[4][2] = {{0.5, -1.0}, {2.0, 0.25}, {-0.75, 3.0}, {1.5, 0.0}};
  for (size_t i = 0; i < rows.size(); ++i) {
    const double design[4] = {rows[i].x, rows[i].y, rows[i].z, 1.0};
    for (int j = 0; j < 4; ++j) a(i, j) = design[j];
    for (int c = 0; c < 2; ++c)
      for (int j = 0; j < 4; ++j) b(i, c) += design[j] * x[j][c];
  }
  const LeastSquaresSolution s = solveLeastSquares(a, b);
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 2; ++c) EXPECT_NEAR(s.coefficients(j, c), x[j][c], 1e-13);
  EXPECT_LT(s.residualRms, 1e-13);
}

// One constant fitted to 1, 2, 3, 4: the mean 2.5, residual RMS sqrt(mean((y - 2.5)^2)) = sqrt(1.25).
TEST(LeastSquares, ConstantFitIsTheMeanWithItsStandardDeviation) {
  DenseMatrix a(4, 1), b(4, 1);
  for (int i = 0; i < 4; ++i) a(i, 0) = 1.0, b(i, 0) = i + 1.0;
  const LeastSquaresSolution s = solveLeastSquares(a, b);
  EXPECT_NEAR(s.coefficients(0, 0), 2.5, 1e-15);
  EXPECT_NEAR(s.residualRms, std::sqrt(1.25), 1e-15);
}

// The residual is per row the Euclidean length over the target columns: two columns with
// residuals (+-1, +-1) give RMS sqrt(2).
TEST(LeastSquares, ResidualIsPerRowEuclidean) {
  DenseMatrix a(2, 1), b(2, 2);
  a(0, 0) = a(1, 0) = 1.0;
  b(0, 0) = b(0, 1) = 1.0;
  b(1, 0) = b(1, 1) = -1.0;
  EXPECT_NEAR(solveLeastSquares(a, b).residualRms, std::sqrt(2.0), 1e-15);
}

// Ridge: one unknown x, rows of ones, targets y_i: x = sum(y) / (n + ridge).
TEST(LeastSquares, RidgeShrinksAsTheClosedFormSays) {
  DenseMatrix a(3, 1), b(3, 1);
  for (int i = 0; i < 3; ++i) a(i, 0) = 1.0, b(i, 0) = 2.0 * i + 1.0;  // 1, 3, 5: sum 9
  EXPECT_NEAR(solveLeastSquares(a, b, 0.5).coefficients(0, 0), 9.0 / 3.5, 1e-14);
}

// The residual of a least-squares solution is orthogonal to every design column.
TEST(LeastSquares, ResidualIsOrthogonalToTheDesign) {
  const auto rows = testing::pseudoRandomColours(30, 0.0, 1.0, 7);
  const auto noise = testing::pseudoRandomColours(30, -0.1, 0.1, 8);
  DenseMatrix a(rows.size(), 3), b(rows.size(), 1);
  for (size_t i = 0; i < rows.size(); ++i) {
    for (int j = 0; j < 3; ++j) a(i, j) = rows[i][j];
    b(i, 0) = rows[i].x * rows[i].y + noise[i].x;
  }
  const LeastSquaresSolution s = solveLeastSquares(a, b);
  for (int j = 0; j < 3; ++j) {
    double dot = 0.0;
    for (size_t i = 0; i < rows.size(); ++i) {
      double fitted = 0.0;
      for (int k = 0; k < 3; ++k) fitted += a(i, k) * s.coefficients(k, 0);
      dot += a(i, j) * (fitted - b(i, 0));
    }
    EXPECT_NEAR(dot, 0.0, 1e-13);
  }
  EXPECT_GT(s.residualRms, 0.01);
}

TEST(LeastSquares, RefusesTooFewRowsAndDependentColumns) {
  DenseMatrix a(2, 3), b(2, 1);
  EXPECT_EQ(expectInputError([&] { solveLeastSquares(a, b); }).key(), "pairs");
  DenseMatrix c(4, 2), d(4, 1);
  for (int i = 0; i < 4; ++i) c(i, 0) = i, c(i, 1) = 2.0 * i, d(i, 0) = i;  // column 1 = 2 x column 0
  EXPECT_EQ(expectInputError([&] { solveLeastSquares(c, d); }).key(), "pairs");
  // A ridge term makes the same problem solvable: the minimum-norm direction (1, 2) / 5 scaled.
  const LeastSquaresSolution s = solveLeastSquares(c, d, 1e-9);
  EXPECT_NEAR(s.coefficients(0, 0), 0.2, 1e-6);
  EXPECT_NEAR(s.coefficients(1, 0), 0.4, 1e-6);
  EXPECT_EQ(expectInputError([&] { solveLeastSquares(c, d, -1.0); }).key(), "ridge");
}

}  // namespace
}  // namespace inim
