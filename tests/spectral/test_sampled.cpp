// Wavelength sampling and the Monte Carlo spectral estimator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "spectral/cie.h"
#include "spectral/sampled.h"
#include "spectral/spectrum.h"

namespace inim {
namespace {

// The visible pdf integrates to 1 over 360-830 nm (to 1e-4), and the inverse CDF used by
// sampleVisibleWavelength matches the numerically integrated CDF (to 1e-3 in u).
TEST(Sampled, VisiblePdfAndInverseCdf) {
  double sum = 0.0;
  const double h = 0.01;
  for (double l = kLambdaMin; l < kLambdaMax; l += h)
    sum += 0.5 * h * (SampledWavelengths::visiblePdf(float(l)) + SampledWavelengths::visiblePdf(float(l + h)));
  EXPECT_NEAR(sum, 1.0, 1e-4);
  EXPECT_EQ(SampledWavelengths::visiblePdf(359.0f), 0.0f);
  EXPECT_EQ(SampledWavelengths::visiblePdf(831.0f), 0.0f);
  for (double u : {0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    float l = SampledWavelengths::sampleVisibleWavelength(float(u));
    ASSERT_GE(l, kLambdaMin);
    ASSERT_LE(l, kLambdaMax);
    double cdf = 0.0;
    for (double x = kLambdaMin; x < l; x += h) cdf += h * SampledWavelengths::visiblePdf(float(x + 0.5 * h));
    EXPECT_NEAR(cdf, u, 1e-3) << u;
  }
}

TEST(Sampled, StratifiedWavelengths) {
  auto w = SampledWavelengths::sampleUniform(0.1f);
  const float delta = (kLambdaMax - kLambdaMin) / 4.0f;
  EXPECT_NEAR(w[0], kLambdaMin + 0.1f * (kLambdaMax - kLambdaMin), 1e-3f);
  for (int i = 1; i < 4; ++i) {
    float d = std::fmod(w[i] - w[i - 1] + (kLambdaMax - kLambdaMin), kLambdaMax - kLambdaMin);
    EXPECT_NEAR(d, delta, 1e-3f);
    EXPECT_GE(w[i], kLambdaMin);
    EXPECT_LE(w[i], kLambdaMax);
    EXPECT_FLOAT_EQ(w.pdf()[i], 1.0f / (kLambdaMax - kLambdaMin));
  }
  auto v = SampledWavelengths::sampleVisible(0.8f);
  for (int i = 0; i < 4; ++i) {
    EXPECT_GE(v[i], kLambdaMin);
    EXPECT_LE(v[i], kLambdaMax);
    EXPECT_FLOAT_EQ(v.pdf()[i], SampledWavelengths::visiblePdf(v[i]));
  }
  // Over the whole range of u (the pdf from the inverse CDF's argument, not from lambda): the
  // pdf is visiblePdf at the wavelength drawn, and lambda stays in the visible range.
  double worst = 0.0;
  for (int k = 0; k <= 4000; ++k) {
    const auto s = SampledWavelengths::sampleVisible(float(k) / 4000.0f * 0.25f);
    for (int i = 0; i < 4; ++i) {
      EXPECT_GE(s[i], kLambdaMin);
      EXPECT_LE(s[i], kLambdaMax);
      const double p = SampledWavelengths::visiblePdf(s[i]);
      worst = std::max(worst, std::abs(double(s.pdf()[i]) - p) / p);
    }
  }
  EXPECT_LT(worst, 2e-6);
  EXPECT_NEAR(v[1], SampledWavelengths::sampleVisibleWavelength(0.05f), 1e-3f);
}

TEST(Sampled, TerminateSecondaryKeepsHeroWithQuarterPdf) {
  auto w = SampledWavelengths::sampleVisible(0.3f);
  float pdf0 = w.pdf()[0];
  EXPECT_FALSE(w.secondaryTerminated());
  w.terminateSecondary();
  EXPECT_TRUE(w.secondaryTerminated());
  EXPECT_FLOAT_EQ(w.pdf()[0], pdf0 / 4.0f);
  for (int i = 1; i < 4; ++i) EXPECT_EQ(w.pdf()[i], 0.0f);
  w.terminateSecondary();  // idempotent
  EXPECT_FLOAT_EQ(w.pdf()[0], pdf0 / 4.0f);
}

TEST(Sampled, SampledSpectrumArithmetic) {
  SampledSpectrum a(2.0f), b;
  b[0] = 1; b[1] = 0; b[2] = 4; b[3] = 2;
  SampledSpectrum q = a.safeDiv(b);
  EXPECT_EQ(q[0], 2.0f);
  EXPECT_EQ(q[1], 0.0f);
  EXPECT_EQ(q[2], 0.5f);
  EXPECT_EQ((a * b).maxValue(), 8.0f);
  EXPECT_FLOAT_EQ((a + b).average(), 3.75f);
  EXPECT_FALSE(a.isBlack());
  EXPECT_TRUE(SampledSpectrum().isBlack());
}

// Mean of sampledToXYZ over n stratified u (one jittered u per stratum).
Vec3d estimate(const Spectrum& s, int n, bool visible, bool terminate, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  Vec3d sum(0.0);
  for (int i = 0; i < n; ++i) {
    float u = std::min((i + U(rng)) / n, 0.99999994f);
    auto w = visible ? SampledWavelengths::sampleVisible(u) : SampledWavelengths::sampleUniform(u);
    if (terminate) w.terminateSecondary();
    sum += Vec3d(sampledToXYZ(s.sample(w), w));
  }
  return sum / double(n);
}

// Tolerance: 0.5% of the trapezoid value with 4096 stratified samples (x 4 wavelengths).
TEST(Sampled, EstimatorMatchesTrapezoid) {
  BlackbodySpectrum bb(5000.0f);
  for (const Spectrum* s : {static_cast<const Spectrum*>(&bb), static_cast<const Spectrum*>(&cie::D65())}) {
    Vec3d ref = spectrumToXYZ(*s);
    for (bool visible : {true, false}) {
      Vec3d est = estimate(*s, 4096, visible, false, 1);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(est[c] / ref[c], 1.0, 5e-3) << visible << c;
      std::cout << "[ info ] " << (visible ? "visible" : "uniform") << " Y rel. error "
                << est.y / ref.y - 1.0 << "\n";
    }
  }
}

// After terminateSecondary() the hero-only estimator is still unbiased: the mean of many
// independent estimates is within 4 standard errors of the exact value.
TEST(Sampled, TerminatedEstimatorIsUnbiased) {
  BlackbodySpectrum bb(5000.0f);
  Vec3d ref = spectrumToXYZ(bb);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const int n = 200000;
  for (bool visible : {true, false}) {
    Vec3d sum(0.0), sum2(0.0);
    for (int i = 0; i < n; ++i) {
      float u = U(rng);
      auto w = visible ? SampledWavelengths::sampleVisible(u) : SampledWavelengths::sampleUniform(u);
      w.terminateSecondary();
      Vec3d e(sampledToXYZ(bb.sample(w), w));
      sum += e;
      sum2 += e * e;
    }
    Vec3d mean = sum / double(n);
    Vec3d sigma = glm::sqrt((sum2 / double(n) - mean * mean) / double(n));
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(std::abs(mean[c] - ref[c]), 4.0 * sigma[c]) << visible << c;
      EXPECT_LT(sigma[c] / ref[c], 0.01);  // enough samples for the check to mean something
    }
  }
}

// White furnace through the estimator: a constant 1 under illuminant E estimates Y = 1.
TEST(Sampled, WhiteFurnaceEstimator) {
  ConstantSpectrum one(1.0f);
  Vec3d est = estimate(one, 4096, true, false, 5);
  EXPECT_NEAR(est.y, 1.0, 1e-3);
}

}  // namespace
}  // namespace inim
