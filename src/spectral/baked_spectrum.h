#pragma once
// A spectrum baked into a dense table at 1 nm over 360-830 nm (or a constant), so the
// per-ray hot path evaluates spectra with a lerp instead of virtual calls and searches.
// Copies share one table (a scene of a million lights made from one emitter holds one).
#include <immintrin.h>

#include <memory>
#include <vector>

#include "spectral/sampled.h"
#include "spectral/spectrum.h"

namespace inim {

class BakedSpectrum {
 public:
  BakedSpectrum() = default;  // zero everywhere
  explicit BakedSpectrum(float c) : c_(c) {}
  // Bakes s(lambda) * scale. Constant spectra (Spectrum::constantValue) stay constant (exact).
  explicit BakedSpectrum(const Spectrum& s, float scale = 1.0f);

  bool isConstant() const { return size_ == 0; }
  INIM_SS_INLINE float operator()(float lambdaNm) const {
    if (size_ == 0) return c_;
    float x = lambdaNm - kLambdaMin;
    if (!(x > 0.0f)) return table_[0];
    if (x >= float(size_ - 1)) return table_[size_ - 1];
    int i = int(x);
    float f = x - float(i);
    return table_[i] + f * (table_[i + 1] - table_[i]);
  }
  // The 4 lanes are computed in registers and stored once (element-wise writes read back
  // as one vector stall on store forwarding in the hot path).
  INIM_SS_INLINE SampledSpectrum sample(const SampledWavelengths& lambda) const {
    static_assert(kNumWavelengths == 4, "SSE lanes");
    if (size_ == 0) return SampledSpectrum(c_);
    SampledSpectrum s;
    _mm_storeu_ps(&s[0], _mm_setr_ps((*this)(lambda[0]), (*this)(lambda[1]), (*this)(lambda[2]),
                                     (*this)(lambda[3])));
    return s;
  }
  float maxValue() const;
  float minValue() const;
  float average() const;  // mean over 360-830 nm
  // Luminance-weighted value: integral(s * ybar) / integral(ybar).
  float luminance() const;
  BakedSpectrum scaled(float s) const;
  // Applies f to every value (e.g. -log(T)/d for an absorption coefficient).
  template <class F>
  BakedSpectrum map(F f) const {
    if (size_ == 0) return BakedSpectrum(f(c_));
    std::vector<float> values(table_, table_ + size_);
    for (float& v : values) v = f(v);
    return BakedSpectrum(std::move(values));
  }

 private:
  explicit BakedSpectrum(std::vector<float> values);
  float c_ = 0.0f;
  // 471 values at 360, 361, ..., 830 nm when not constant: shared, read through a plain
  // pointer so the hot path does not go through the shared_ptr.
  std::shared_ptr<const std::vector<float>> values_;
  const float* table_ = nullptr;
  int size_ = 0;
};

}  // namespace inim
