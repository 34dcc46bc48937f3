#pragma once
// A fixed packet of 4 wavelengths carried by every sample, with their pdfs (pbrt-v4 style).
// Dispersive events "terminate secondary" wavelengths: only the hero wavelength goes on,
// its pdf divided by 4 so the estimator stays unbiased.
#include <algorithm>
#include <array>
#include <cmath>

namespace inim {

constexpr int kNumWavelengths = 4;

// SampledSpectrum is passed in two SSE registers (two 8-byte halves): an out-of-line
// operator reassembles the halves through the stack and stalls on store forwarding, so
// its small members are always inlined, even into large hot functions.
#define INIM_SS_INLINE __attribute__((always_inline)) inline
constexpr float kLambdaMin = 360.0f;  // nm
constexpr float kLambdaMax = 830.0f;

class SampledSpectrum {
 public:
  INIM_SS_INLINE SampledSpectrum() { v_.fill(0.0f); }
  INIM_SS_INLINE explicit SampledSpectrum(float c) { v_.fill(c); }
  INIM_SS_INLINE float& operator[](int i) { return v_[i]; }
  INIM_SS_INLINE float operator[](int i) const { return v_[i]; }

#define INIM_SS_OP(op)                                                          \
  INIM_SS_INLINE SampledSpectrum& operator op##=(const SampledSpectrum& s) {    \
    for (int i = 0; i < kNumWavelengths; ++i) v_[i] op## = s.v_[i];             \
    return *this;                                                               \
  }                                                                             \
  INIM_SS_INLINE SampledSpectrum operator op(const SampledSpectrum& s) const {  \
    SampledSpectrum r = *this;                                                  \
    return r op## = s;                                                          \
  }                                                                             \
  INIM_SS_INLINE SampledSpectrum& operator op##=(float a) {                     \
    for (int i = 0; i < kNumWavelengths; ++i) v_[i] op## = a;                   \
    return *this;                                                               \
  }                                                                             \
  INIM_SS_INLINE SampledSpectrum operator op(float a) const {                   \
    SampledSpectrum r = *this;                                                  \
    return r op## = a;                                                          \
  }
  INIM_SS_OP(+)
  INIM_SS_OP(-)
  INIM_SS_OP(*)
#undef INIM_SS_OP
  // Division that returns 0 where the divisor is 0 (pdf-safe).
  SampledSpectrum safeDiv(const SampledSpectrum& d) const {
    SampledSpectrum r;
    for (int i = 0; i < kNumWavelengths; ++i) r.v_[i] = d.v_[i] != 0.0f ? v_[i] / d.v_[i] : 0.0f;
    return r;
  }
  INIM_SS_INLINE SampledSpectrum operator/(float a) const { return *this * (1.0f / a); }
  INIM_SS_INLINE bool isBlack() const {
    return std::all_of(v_.begin(), v_.end(), [](float x) { return x == 0.0f; });
  }
  float maxValue() const { return *std::max_element(v_.begin(), v_.end()); }
  float average() const { return (v_[0] + v_[1] + v_[2] + v_[3]) * 0.25f; }
  bool hasNaN() const {
    return std::any_of(v_.begin(), v_.end(), [](float x) { return !std::isfinite(x); });
  }

 private:
  std::array<float, kNumWavelengths> v_;
};
INIM_SS_INLINE SampledSpectrum operator*(float a, const SampledSpectrum& s) { return s * a; }

class SampledWavelengths {
 public:
  // Uniform in [lmin, lmax): one uniform u, the other three rotated by 1/4 (stratified).
  static SampledWavelengths sampleUniform(float u, float lmin = kLambdaMin, float lmax = kLambdaMax);
  // Importance-sampled toward the visible (pbrt-v4's 538 nm centred sech^2 pdf), stratified.
  static SampledWavelengths sampleVisible(float u);
  static float visiblePdf(float lambda);
  static float sampleVisibleWavelength(float u);

  INIM_SS_INLINE float operator[](int i) const { return lambda_[i]; }
  INIM_SS_INLINE const SampledSpectrum& pdf() const { return pdf_; }
  // Keep only the hero wavelength (index 0) after a dispersive event.
  void terminateSecondary();
  bool secondaryTerminated() const;

 private:
  std::array<float, kNumWavelengths> lambda_{};
  SampledSpectrum pdf_;
};

}  // namespace inim
