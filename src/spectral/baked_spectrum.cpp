#include "spectral/baked_spectrum.h"

#include <algorithm>

#include "spectral/cie.h"

namespace inim {

BakedSpectrum::BakedSpectrum(const Spectrum& s, float scale) {
  if (const std::optional<float> c = s.constantValue()) {
    c_ = *c * scale;
    return;
  }
  int n = int(kLambdaMax - kLambdaMin) + 1;
  table_.resize(n);
  for (int i = 0; i < n; ++i) table_[i] = s(kLambdaMin + float(i)) * scale;
}

float BakedSpectrum::maxValue() const {
  return table_.empty() ? c_ : *std::max_element(table_.begin(), table_.end());
}
float BakedSpectrum::minValue() const {
  return table_.empty() ? c_ : *std::min_element(table_.begin(), table_.end());
}
float BakedSpectrum::average() const {
  if (table_.empty()) return c_;
  double sum = 0.0;
  for (size_t i = 0; i + 1 < table_.size(); ++i) sum += 0.5 * (table_[i] + table_[i + 1]);
  return float(sum / double(table_.size() - 1));
}
float BakedSpectrum::luminance() const {
  if (table_.empty()) return c_;
  const Spectrum& y = cie::Y();
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < table_.size(); ++i) {
    double w = (i == 0 || i + 1 == table_.size()) ? 0.5 : 1.0;
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
