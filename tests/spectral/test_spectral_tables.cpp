// The spectral tables of the hot paths: BakedSpectrum (1 nm table or an exact constant) and
// CmfTable (the CIE 1931 CMFs in float on a 1 nm grid), against the spectra they tabulate.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "spectral/baked_spectrum.h"
#include "spectral/cie.h"
#include "spectral/cmf_table.h"
#include "spectral/spectrum.h"

namespace inim {
namespace {

TEST(Spectrum, OnlyAConstantSpectrumHasAConstantValue) {
  EXPECT_EQ(ConstantSpectrum(0.25f).constantValue(), std::optional<float>(0.25f));
  EXPECT_FALSE(GaussianSpectrum(550.0f, 40.0f).constantValue().has_value());
  // A scaled constant is a constant in value but not by construction: it is tabulated.
  EXPECT_FALSE(ScaledSpectrum(std::make_shared<ConstantSpectrum>(2.0f), 3.0f).constantValue().has_value());
}

TEST(BakedSpectrum, ConstantSpectraStayExactConstants) {
  const BakedSpectrum b(ConstantSpectrum(0.3f), 2.5f);
  EXPECT_TRUE(b.isConstant());
  EXPECT_EQ(b(360.0f), 0.3f * 2.5f);
  EXPECT_EQ(b(612.37f), 0.3f * 2.5f);
  EXPECT_EQ(b.luminance(), 0.3f * 2.5f);
  const BakedSpectrum scaled(ScaledSpectrum(std::make_shared<ConstantSpectrum>(2.0f), 3.0f));
  EXPECT_FALSE(scaled.isConstant());
  EXPECT_FLOAT_EQ(scaled(500.5f), 6.0f);
  EXPECT_NEAR(scaled.luminance(), 6.0f, 1e-5f);
  EXPECT_NEAR(scaled.average(), 6.0f, 1e-5f);
}

// A piecewise-linear spectrum with knots on whole nanometres is reproduced exactly by the 1 nm
// table's interpolation (to float rounding), and held constant beyond 360-830 nm.
TEST(BakedSpectrum, TableReproducesAPiecewiseLinearSpectrum) {
  const PiecewiseLinearSpectrum s({360.0f, 450.0f, 451.0f, 700.0f, 830.0f}, {0.1f, 0.9f, 0.2f, 0.6f, 0.4f});
  const BakedSpectrum b(s, 2.0f);
  EXPECT_FALSE(b.isConstant());
  for (float l = 360.0f; l <= 830.0f; l += 0.37f) EXPECT_NEAR(b(l), 2.0f * s(l), 2e-6f) << l;
  EXPECT_EQ(b(300.0f), b(360.0f));
  EXPECT_EQ(b(900.0f), b(830.0f));
  EXPECT_NEAR(b.maxValue(), 1.8f, 1e-6f);
  EXPECT_NEAR(b.minValue(), 0.2f, 1e-6f);
}

// Copies (which share one table: a million area lights of one emitter hold one) read the same
// values, and map() and
// scaled() make new tables without touching the one they came from.
TEST(BakedSpectrum, CopiesShareTheirTableAndMapLeavesTheOriginal) {
  const BakedSpectrum a(GaussianSpectrum(550.0f, 40.0f));
  const BakedSpectrum copy = a;
  const BakedSpectrum doubled = a.scaled(2.0f);
  for (float l = 360.0f; l <= 830.0f; l += 7.3f) {
    EXPECT_EQ(copy(l), a(l)) << l;
    EXPECT_NEAR(doubled(l), 2.0f * a(l), 1e-6f * a(l) + 1e-30f) << l;
  }
  EXPECT_EQ(a.map([](float) { return 1.0f; })(500.0f), 1.0f);
  EXPECT_EQ(a(500.0f), GaussianSpectrum(550.0f, 40.0f)(500.0f));
}

// The CMF table is cie::X/Y/Z divided by the y-bar integral; its Monte Carlo XYZ agrees with
// the double-precision sampledToXYZ.
TEST(CmfTable, MatchesTheCieFunctionsAndSampledToXYZ) {
  const CmfTable& t = cmfTable();
  const double norm = 1.0 / cie::yIntegral();
  for (float l = 360.0f; l <= 830.0f; l += 0.5f) {
    const Vec3 v = t(l);
    EXPECT_NEAR(v.x, cie::X()(l) * norm, 1e-6) << l;
    EXPECT_NEAR(v.y, cie::Y()(l) * norm, 1e-6) << l;
    EXPECT_NEAR(v.z, cie::Z()(l) * norm, 1e-6) << l;
  }
  EXPECT_EQ(t(359.0f), Vec3(0.0f));
  EXPECT_EQ(t(831.0f), Vec3(0.0f));
  SampledSpectrum L;
  for (int k = 0; k < kNumWavelengths; ++k) L[k] = 0.5f + 0.25f * float(k);
  for (float u : {0.03f, 0.41f, 0.77f}) {
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(u);
    const Vec3 a = t.toXYZ(L, wl), b = sampledToXYZ(L, wl);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f * std::max(1.0f, std::abs(b[c]))) << u;
  }
}

}  // namespace
}  // namespace inim
