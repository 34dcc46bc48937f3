// 3D LUT: tetrahedral interpolation, sampling and inversion of a forward function.
#include <gtest/gtest.h>

#include <algorithm>

#include "calibration/lut3d.h"
#include "calibration/test_functions.h"
#include "expect_input_error.h"

namespace inim {
namespace {

TEST(Lut3d, IdentityIsIdentity) {
  const Lut3d lut;
  EXPECT_EQ(lut.size(), 33);
  for (const Vec3d& x : testing::pseudoRandomColours(200)) {
    const Vec3d y = lut.eval(x);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(y[c], x[c], 1e-15);
  }
}

// Each tetrahedron's weights are barycentric, so every affine function is reproduced exactly,
// whatever the table size (even 2 nodes per axis) and in all six tetrahedra.
TEST(Lut3d, TetrahedralReproducesAffineFunctions) {
  const glm::dmat3 a = glm::dmat3(0.9, -0.3, 0.2, 0.4, 1.1, -0.6, 0.05, 0.25, 0.7);
  const Vec3d offset(0.1, -0.2, 0.3);
  auto affine = [&](const Vec3d& x) { return a * x + offset; };
  for (int size : {2, 5, 33}) {
    const Lut3d lut = Lut3d::sample(affine, size);
    for (const Vec3d& x : testing::pseudoRandomColours(300, 0.0, 1.0, size)) {
      const Vec3d d = lut.eval(x) - affine(x);
      EXPECT_NEAR(glm::length(d), 0.0, 1e-14) << "size " << size;
    }
  }
}

// Non-linear table: nodes come back exactly; on the cell diagonal r = g = b the interpolation
// is the straight line between the cell's corners (0,0,0) and (1,1,1).
TEST(Lut3d, NodesExactAndDiagonalLinear) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 9);
  for (int i : {0, 3, 8})
    for (int j : {0, 5, 8}) EXPECT_EQ(lut.eval(lut.node(i, j, 8 - i)), testing::asymmetric(lut.node(i, j, 8 - i)));
  const double f = 0.3, lo = 2.0 / 8.0, hi = 3.0 / 8.0;
  const Vec3d expected = (1 - f) * testing::asymmetric(Vec3d(lo)) + f * testing::asymmetric(Vec3d(hi));
  EXPECT_NEAR(glm::length(lut.eval(Vec3d(lo + f / 8.0)) - expected), 0.0, 1e-15);
}

// Inputs outside the domain are clamped to it, as OpenColorIO does for its LUT3D.
TEST(Lut3d, ClampsOutsideTheDomain) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 17);
  EXPECT_EQ(lut.eval(Vec3d(-0.5, 1.5, 0.25)), lut.eval(Vec3d(0.0, 1.0, 0.25)));
  EXPECT_EQ(lut.eval(Vec3d(2.0)), testing::asymmetric(Vec3d(1.0)));
}

TEST(Lut3d, RefusesBadSizesAndDumpsItsTable) {
  EXPECT_EQ(expectInputError([] { Lut3d(1); }).key(), "lut_size");
  EXPECT_EQ(expectInputError([] { Lut3d(257); }).key(), "lut_size");
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 3);
  const nlohmann::json p = lut.parameters();
  EXPECT_EQ(p["size"], 3);
  ASSERT_EQ(p["table"].size(), 27u);
  EXPECT_EQ(p["table"][1][0].get<double>(), lut.at(1, 0, 0).x);  // red fastest
}

// A display-like forward map: per-channel monotone response, then mixing with positive
// crosstalk; rows sum to 1 so F(0) = 0 and F(1) = 1. Its inverse is analytic.
const glm::dmat3& crosstalk() {
  static const glm::dmat3 m = glm::transpose(glm::dmat3(0.80, 0.15, 0.05,  //
                                                        0.10, 0.85, 0.05,  //
                                                        0.02, 0.08, 0.90));
  return m;
}
Vec3d response(const Vec3d& x) { return (x + 0.3 * x * x) / 1.3; }
Vec3d forward(const Vec3d& x) { return crosstalk() * response(x); }
// The drive with F(drive) = t (unclamped): undo the mixing, then solve 0.3 u^2 + u = 1.3 v.
Vec3d analyticInverse(const Vec3d& t) {
  const Vec3d v = glm::inverse(crosstalk()) * t;
  Vec3d u;
  for (int c = 0; c < 3; ++c) u[c] = (-1.0 + std::sqrt(1.0 + 1.2 * 1.3 * v[c])) / 0.6;
  return u;
}

TEST(Lut3d, InverseOfADisplayResponse) {
  const InverseLut inverse = invertToLut(forward);
  const Lut3d& lut = inverse.lut;
  const int n = lut.size();
  size_t outside = 0;
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const Vec3d t = lut.node(r, g, b), exact = analyticInverse(t), drive = lut.at(r, g, b);
        const double residual = inverse.residuals[size_t(r) + n * (g + size_t(n) * b)];
        EXPECT_EQ(drive, glm::clamp(drive, Vec3d(0.0), Vec3d(1.0)));
        EXPECT_NEAR(residual, glm::length(forward(drive) - t), 1e-15);
        const Vec3d excess = glm::max(-exact, exact - 1.0);
        // > 0: outside F's range (up to the analytic inverse's own rounding, 1e-12)
        const double beyond = std::max({excess.x, excess.y, excess.z});
        if (beyond <= 1e-12) {
          EXPECT_NEAR(glm::length(drive - exact), 0.0, 1e-6) << "target " << r << " " << g << " " << b;
          EXPECT_LE(residual, 1e-6);
        } else {
          ++outside;
          // Out of range: no worse than clipping the exact inverse, and reported.
          EXPECT_LE(residual, glm::length(forward(glm::clamp(exact, Vec3d(0.0), Vec3d(1.0))) - t) + 1e-12);
          if (beyond > 1e-4) {
            EXPECT_GT(residual, 1e-6);
          }
        }
      }
  EXPECT_GT(outside, size_t(n * n));  // saturated colours lie outside a display with crosstalk
  EXPECT_EQ(inverse.unreachedCount, outside);
  EXPECT_GT(inverse.maxResidual, 0.01);
}

TEST(Lut3d, InverseOfIdentityIsIdentityAndDeterministic) {
  InversionSettings settings;
  settings.size = 9;
  const InverseLut a = invertToLut([](const Vec3d& x) { return x; }, settings);
  EXPECT_EQ(a.unreachedCount, 0u);
  for (int b = 0; b < 9; ++b)
    for (int g = 0; g < 9; ++g)
      for (int r = 0; r < 9; ++r) EXPECT_NEAR(glm::length(a.lut.at(r, g, b) - a.lut.node(r, g, b)), 0.0, 1e-12);
  const InverseLut first = invertToLut(forward, settings), second = invertToLut(forward, settings);
  EXPECT_EQ(first.lut.values(), second.lut.values());
}

TEST(Lut3d, InverseRefusesNonFiniteForward) {
  InversionSettings settings;
  settings.size = 3;
  EXPECT_EQ(expectInputError([&] { invertToLut([](const Vec3d& x) { return x / x.x; }, settings); }).key(), "forward");
}

}  // namespace
}  // namespace inim
