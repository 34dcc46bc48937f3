#include "spectral/sampled.h"

namespace inim {

float SampledWavelengths::visiblePdf(float lambda) {
  if (lambda < kLambdaMin || lambda > kLambdaMax) return 0.0f;
  float c = std::cosh(0.0072f * (lambda - 538.0f));
  return 0.0039398042f / (c * c);
}

namespace {

// The inverse CDF's argument: lambda = 538 - 138.888889 atanh(x).
float visibleArgument(float u) { return 0.85691062f - 1.82750197f * u; }

// atanh(x) = ln((1 + x) / (1 - x)) / 2, one logarithm (|x| < 0.98 here, far from the poles).
float visibleWavelengthOf(float x) { return 538.0f - 69.4444445f * std::log((1.0f + x) / (1.0f - x)); }

}  // namespace

float SampledWavelengths::sampleVisibleWavelength(float u) { return visibleWavelengthOf(visibleArgument(u)); }

SampledWavelengths SampledWavelengths::sampleUniform(float u, float lmin, float lmax) {
  SampledWavelengths w;
  w.lambda_[0] = (1.0f - u) * lmin + u * lmax;
  float delta = (lmax - lmin) / kNumWavelengths;
  for (int i = 1; i < kNumWavelengths; ++i) {
    w.lambda_[i] = w.lambda_[i - 1] + delta;
    if (w.lambda_[i] > lmax) w.lambda_[i] = lmin + (w.lambda_[i] - lmax);
  }
  for (int i = 0; i < kNumWavelengths; ++i) w.pdf_[i] = 1.0f / (lmax - lmin);
  return w;
}

SampledWavelengths SampledWavelengths::sampleVisible(float u) {
  SampledWavelengths w;
  for (int i = 0; i < kNumWavelengths; ++i) {
    float up = u + float(i) / kNumWavelengths;
    if (up > 1.0f) up -= 1.0f;
    // visiblePdf without its cosh: 0.0072 x 138.888889 = 1, and cosh^2(atanh x) = 1 / (1 - x^2).
    const float x = visibleArgument(up);
    w.lambda_[i] = visibleWavelengthOf(x);
    w.pdf_[i] = w.lambda_[i] >= kLambdaMin && w.lambda_[i] <= kLambdaMax ? 0.0039398042f * (1.0f - x * x) : 0.0f;
  }
  return w;
}

void SampledWavelengths::terminateSecondary() {
  if (secondaryTerminated()) return;
  for (int i = 1; i < kNumWavelengths; ++i) pdf_[i] = 0.0f;
  pdf_[0] /= kNumWavelengths;
}

bool SampledWavelengths::secondaryTerminated() const {
  for (int i = 1; i < kNumWavelengths; ++i)
    if (pdf_[i] != 0.0f) return false;
  return true;
}

}  // namespace inim
