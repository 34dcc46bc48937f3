#include "spectral/baked_spectrum.h"

#include <algorithm>

#include "spectral/cie.h"

namespace inim {

BakedSpectrum::BakedSpectrum(const Spectrum& s, float scale) {
  if (const std::optional<float> c = s.constantValue()) {
    c_ = *c * scale;
    return;
  }
  std::vector<float> values(size_t(kLambdaMax - kLambdaMin) + 1);
  for (size_t i = 0; i < values.size(); ++i) values[i] = s(kLambdaMin + float(i)) * scale;
  *this = BakedSpectrum(std::move(values));
}

BakedSpectrum::BakedSpectrum(std::vector<float> values)
    : values_(std::make_shared<const std::vector<float>>(std::move(values))),
      table_(values_->data()),
      size_(int(values_->size())) {}

float BakedSpectrum::maxValue() const {
  return size_ == 0 ? c_ : *std::max_element(table_, table_ + size_);
}
float BakedSpectrum::minValue() const {
  return size_ == 0 ? c_ : *std::min_element(table_, table_ + size_);
}
float BakedSpectrum::average() const {
  if (size_ == 0) return c_;
  double sum = 0.0;
  for (int i = 0; i + 1 < size_; ++i) sum += 0.5 * (table_[i] + table_[i + 1]);
  return float(sum / double(size_ - 1));
}
float BakedSpectrum::luminance() const {
  if (size_ == 0) return c_;
  const Spectrum& y = cie::Y();
  double num = 0.0, den = 0.0;
  for (int i = 0; i < size_; ++i) {
    double w = (i == 0 || i + 1 == size_) ? 0.5 : 1.0;
    double yb = y(kLambdaMin + float(i));
    num += w * table_[i] * yb;
    den += w * yb;
  }
  return den > 0.0 ? float(num / den) : 0.0f;
}
BakedSpectrum BakedSpectrum::scaled(float s) const {
  return map([s](float v) { return v * s; });
}

}  // namespace inim
