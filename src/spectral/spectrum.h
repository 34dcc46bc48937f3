#pragma once
// Spectral distributions: values as a function of wavelength in nm.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "spectral/sampled.h"

namespace inim {

class Spectrum {
 public:
  virtual ~Spectrum() = default;
  virtual float operator()(float lambdaNm) const = 0;
  virtual float maxValue() const = 0;
  virtual SampledSpectrum sample(const SampledWavelengths& lambda) const {
    SampledSpectrum s;
    for (int i = 0; i < kNumWavelengths; ++i) s[i] = (*this)(lambda[i]);
    return s;
  }
  // The value at every wavelength when the spectrum is a constant by construction
  // (ConstantSpectrum), so that users can keep it as one number; nothing otherwise.
  virtual std::optional<float> constantValue() const { return std::nullopt; }
};
using SpectrumPtr = std::shared_ptr<const Spectrum>;

class ConstantSpectrum final : public Spectrum {
 public:
  explicit ConstantSpectrum(float c) : c_(c) {}
  float operator()(float) const override { return c_; }
  float maxValue() const override { return c_; }
  std::optional<float> constantValue() const override { return c_; }

 private:
  float c_;
};

// Piecewise linear through (lambda, value) points; zero outside the table.
class PiecewiseLinearSpectrum final : public Spectrum {
 public:
  PiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values,
                          std::string source = "");
  float operator()(float lambdaNm) const override;
  float maxValue() const override;
  const std::vector<float>& lambdas() const { return lambdas_; }
  const std::vector<float>& values() const { return values_; }
  const std::string& source() const { return source_; }  // comment header of its file
  void scale(float s);

 private:
  std::vector<float> lambdas_, values_;
  std::string source_;
};

// Planck's law at temperature T (K), normalised to a peak of 1.
class BlackbodySpectrum final : public Spectrum {
 public:
  explicit BlackbodySpectrum(float temperatureK);
  float operator()(float lambdaNm) const override;
  float maxValue() const override { return 1.0f; }
  // Unnormalised spectral radiance, W / (m^2 sr m).
  static double planck(double lambdaNm, double temperatureK);

 private:
  float T_, normalization_;
};

// scale * exp(-(lambda - mean)^2 / (2 sigma^2)); used for documented placeholder spectra.
class GaussianSpectrum final : public Spectrum {
 public:
  GaussianSpectrum(float meanNm, float fwhmNm, float scale = 1.0f);
  float operator()(float lambdaNm) const override;
  float maxValue() const override { return scale_; }

 private:
  float mean_, sigma_, scale_;
};

// A product of spectra (e.g. a filter over an illuminant).
class ScaledSpectrum final : public Spectrum {
 public:
  ScaledSpectrum(SpectrumPtr s, float scale) : s_(std::move(s)), scale_(scale) {}
  float operator()(float l) const override { return scale_ * (*s_)(l); }
  float maxValue() const override { return scale_ * s_->maxValue(); }

 private:
  SpectrumPtr s_;
  float scale_;
};

// Reads column `column` (a header name, e.g. "relative_power", "n", "r") of a CSV whose
// first non-comment line names the columns and whose first column is wavelength_nm.
// Lines starting with '#' are kept as the source. Throws InputError naming file/column.
std::shared_ptr<PiecewiseLinearSpectrum> loadSpectrumCSV(const std::string& path,
                                                         const std::string& column);
// All columns but the first, in order.
std::vector<std::string> csvColumns(const std::string& path);

// Integral of s over [lmin, lmax] by 1 nm trapezoid.
double integrate(const Spectrum& s, float lmin = kLambdaMin, float lmax = kLambdaMax);

}  // namespace inim
