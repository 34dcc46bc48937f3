// 3x3 matrix (free and white-preserving) and root-polynomial colour corrections.
#include <gtest/gtest.h>

#include "calibration/colour_models.h"
#include "calibration/test_functions.h"
#include "expect_input_error.h"

namespace inim {
namespace {

// A camera-like matrix: rows mix the channels, not symmetric.
glm::dmat3 knownMatrix() {
  return glm::transpose(glm::dmat3(1.20, -0.15, -0.05,  //
                                   -0.10, 1.05, 0.05,   //
                                   0.02, -0.22, 1.20));
}

ColourPairs pairsFrom(const std::vector<Vec3d>& sources, const ColourFunction& f) {
  ColourPairs pairs{sources, {}};
  for (const Vec3d& s : sources) pairs.targets.push_back(f(s));
  return pairs;
}

// Targets with a non-linear part that no 3x3 matrix (nor root-polynomial) can follow.
ColourPairs nonlinearPairs() {
  return pairsFrom(testing::pseudoRandomColours(60, 0.05, 1.0, 3), [](const Vec3d& x) {
    return knownMatrix() * x + 0.1 * Vec3d(x.x * x.x, x.y * x.z, std::sin(3.0 * x.z));
  });
}

void expectMatrixNear(const glm::dmat3& a, const glm::dmat3& b, double tolerance) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << "row " << r << " column " << c;
}

TEST(MatrixModel, RecoversTheMatrixThatMadeTheData) {
  const glm::dmat3 m = knownMatrix();
  const MatrixModel model = MatrixModel::fit(pairsFrom(testing::pseudoRandomColours(24), [&](const Vec3d& x) { return m * x; }));
  expectMatrixNear(model.matrix(), m, 1e-13);
  EXPECT_LT(model.residualRms(), 1e-14);
  EXPECT_FALSE(model.preservesWhite());
}

// The white constraint holds to rounding even on data the matrix cannot fit, and costs
// residual: the constrained optimum is never below the free one.
TEST(MatrixModel, WhitePreservingMapsTheWhiteExactly) {
  const ColourPairs pairs = nonlinearPairs();
  const Vec3d sourceWhite(0.9, 1.0, 1.1), targetWhite(0.95047, 1.0, 1.08883);
  const MatrixModel free = MatrixModel::fit(pairs);
  const MatrixModel white = MatrixModel::fitPreservingWhite(pairs, sourceWhite, targetWhite);
  const Vec3d mapped = white.apply(sourceWhite);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mapped[c], targetWhite[c], 1e-14);
  EXPECT_GT(glm::length(free.apply(sourceWhite) - targetWhite), 1e-4);  // the free fit does not
  EXPECT_GE(white.residualRms(), free.residualRms());
  EXPECT_TRUE(white.preservesWhite());
  // Its residual is what apply() gives on the pairs.
  double sum = 0.0;
  for (size_t i = 0; i < pairs.sources.size(); ++i) {
    const Vec3d d = white.apply(pairs.sources[i]) - pairs.targets[i];
    sum += glm::dot(d, d);
  }
  EXPECT_NEAR(white.residualRms(), std::sqrt(sum / double(pairs.sources.size())), 1e-14);
}

// When the data come from a matrix that already maps the white, the constraint changes nothing.
TEST(MatrixModel, WhitePreservingRecoversAConsistentMatrix) {
  const glm::dmat3 m = knownMatrix();
  const Vec3d sourceWhite(1.0, 1.0, 1.0);
  const MatrixModel model = MatrixModel::fitPreservingWhite(
      pairsFrom(testing::pseudoRandomColours(24), [&](const Vec3d& x) { return m * x; }), sourceWhite, m * sourceWhite);
  expectMatrixNear(model.matrix(), m, 1e-13);
}

// Terms of degree 1 only: f(k x) = k f(x). With k a power of two every operation scales
// exactly, so the equality is bit-exact; for other k it holds to rounding.
TEST(RootPolynomialModel, ExposureInvariant) {
  const RootPolynomialModel model = RootPolynomialModel::fit(nonlinearPairs());
  for (const Vec3d& x : testing::pseudoRandomColours(50, 0.0, 1.0, 11)) {
    for (double k : {4.0, 0.25, 2.0}) {
      const Vec3d scaled = model.apply(k * x), expected = k * model.apply(x);
      EXPECT_EQ(scaled.x, expected.x);
      EXPECT_EQ(scaled.y, expected.y);
      EXPECT_EQ(scaled.z, expected.z);
    }
    const Vec3d scaled = model.apply(3.7 * x), expected = 3.7 * model.apply(x);
    EXPECT_NEAR(glm::length(scaled - expected), 0.0, 1e-13 * glm::length(expected));
  }
}

// Data from a 3x3 matrix: the root terms get zero weight and the matrix comes back exactly.
TEST(RootPolynomialModel, ReproducesAMatrixExactly) {
  const glm::dmat3 m = knownMatrix();
  const RootPolynomialModel model =
      RootPolynomialModel::fit(pairsFrom(testing::pseudoRandomColours(40), [&](const Vec3d& x) { return m * x; }));
  for (int out = 0; out < 3; ++out) {
    for (int in = 0; in < 3; ++in) EXPECT_NEAR(model.coefficients()[out][in], m[in][out], 1e-12);
    for (int t = 3; t < RootPolynomialModel::kTerms; ++t) EXPECT_NEAR(model.coefficients()[out][t], 0.0, 1e-12);
  }
  EXPECT_LT(model.residualRms(), 1e-13);
}

// Data made by a root-polynomial come back exactly; on non-linear data it fits no worse than a
// matrix (its terms include the matrix's).
TEST(RootPolynomialModel, RecoversItsOwnFormAndBeatsTheMatrix) {
  RootPolynomialModel::Coefficients c{};
  c[0] = {1.0, 0.1, 0.0, 0.2, -0.1, 0.05};
  c[1] = {0.0, 0.9, 0.1, -0.05, 0.3, 0.0};
  c[2] = {0.05, -0.1, 1.1, 0.0, 0.1, -0.2};
  const RootPolynomialModel truth(c);
  const RootPolynomialModel fitted = RootPolynomialModel::fit(
      pairsFrom(testing::pseudoRandomColours(40), [&](const Vec3d& x) { return truth.apply(x); }));
  for (int out = 0; out < 3; ++out)
    for (int t = 0; t < RootPolynomialModel::kTerms; ++t) EXPECT_NEAR(fitted.coefficients()[out][t], c[out][t], 1e-12);
  const ColourPairs pairs = nonlinearPairs();
  EXPECT_LE(RootPolynomialModel::fit(pairs).residualRms(), MatrixModel::fit(pairs).residualRms());
}

TEST(RootPolynomialModel, NegativeProductsContributeZero) {
  const auto t = RootPolynomialModel::terms(Vec3d(-0.25, 0.5, 0.5));
  EXPECT_EQ(t[3], 0.0);  // sqrt(r g), r g < 0
  EXPECT_EQ(t[4], 0.5);  // sqrt(g b)
  EXPECT_EQ(t[5], 0.0);  // sqrt(r b)
}

TEST(ColourModels, ParametersDescribeTheModel) {
  const MatrixModel matrix(knownMatrix());
  const nlohmann::json p = matrix.parameters();
  EXPECT_EQ(p["model"], "matrix_3x3");
  EXPECT_EQ(p["matrix_rows"][0][1].get<double>(), -0.15);  // row 0, column 1
  EXPECT_EQ(p["matrix_rows"][2][1].get<double>(), -0.22);
  const RootPolynomialModel root = RootPolynomialModel::fit(nonlinearPairs());
  const nlohmann::json q = root.parameters();
  EXPECT_EQ(q["model"], "root_polynomial_2");
  EXPECT_EQ(q["terms"][3], "sqrt(r*g)");
  EXPECT_EQ(q["coefficients"][1][4].get<double>(), root.coefficients()[1][4]);
  EXPECT_EQ(q["fit_residual_rms"].get<double>(), root.residualRms());
}

TEST(ColourModels, RefuseMismatchedOrNonFinitePairs) {
  ColourPairs pairs{testing::pseudoRandomColours(5), testing::pseudoRandomColours(4)};
  EXPECT_EQ(expectInputError([&] { MatrixModel::fit(pairs); }).key(), "pairs");
  pairs.targets.push_back(Vec3d(std::nan(""), 0.0, 0.0));
  const InputError e = expectInputError([&] { RootPolynomialModel::fit(pairs); });
  EXPECT_EQ(e.value(), "pair 4");
  EXPECT_EQ(expectInputError([&] { RootPolynomialModel::fit({testing::pseudoRandomColours(5), testing::pseudoRandomColours(5)}); }).key(),
            "pairs");  // 5 pairs for 6 unknowns
}

}  // namespace
}  // namespace inim
