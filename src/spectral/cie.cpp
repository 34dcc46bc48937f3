#include "spectral/cie.h"

#include "core/output_file.h"

namespace inim {

namespace cie {
namespace {
const std::string kCmf = "spectra/cie1931_2deg_cmf.csv";
std::shared_ptr<PiecewiseLinearSpectrum> load(const std::string& rel, const std::string& col) {
  return loadSpectrumCSV(dataPath(rel), col);
}
}  // namespace

const PiecewiseLinearSpectrum& X() {
  static const auto s = load(kCmf, "x_bar");
  return *s;
}
const PiecewiseLinearSpectrum& Y() {
  static const auto s = load(kCmf, "y_bar");
  return *s;
}
const PiecewiseLinearSpectrum& Z() {
  static const auto s = load(kCmf, "z_bar");
  return *s;
}
const PiecewiseLinearSpectrum& D65() {
  static const auto s = load("spectra/cie_d65.csv", "relative_power");
  return *s;
}
const PiecewiseLinearSpectrum& A() {
  static const auto s = load("spectra/cie_a.csv", "relative_power");
  return *s;
}

double yIntegral() {
  static const double v = integrate(Y(), kLambdaMin, kLambdaMax);
  return v;
}
}  // namespace cie

namespace {
// Unnormalised 1 nm trapezoid integrals of f * (x_bar, y_bar, z_bar) over 360-830 nm.
template <class F>
Vec3d integrateXYZ(F&& f) {
  const auto& X = cie::X();
  const auto& Y = cie::Y();
  const auto& Z = cie::Z();
  Vec3d sum(0.0);
  const int n0 = int(kLambdaMin), n1 = int(kLambdaMax);
  for (int l = n0; l <= n1; ++l) {
    float lf = float(l);
    double v = f(lf);
    double w = (l == n0 || l == n1) ? 0.5 : 1.0;
    sum += w * v * Vec3d(X(lf), Y(lf), Z(lf));
  }
  return sum;
}
}  // namespace

Vec3d d65WhiteXyz() {
  static const Vec3d white = [] {
    const Vec3d w = spectrumToXYZ(cie::D65());
    return w / w.y;
  }();
  return white;
}

Vec3d spectrumToXYZ(const Spectrum& s) {
  return integrateXYZ([&](float l) { return double(s(l)); }) / cie::yIntegral();
}

Vec3d reflectanceToXYZ(const Spectrum& r, const Spectrum& illuminant) {
  Vec3d xyz = integrateXYZ([&](float l) { return double(r(l)) * double(illuminant(l)); });
  double norm = integrateXYZ([&](float l) { return double(illuminant(l)); }).y;
  return norm > 0.0 ? xyz / norm : Vec3d(0.0);
}

Vec3 sampledToXYZ(const SampledSpectrum& L, const SampledWavelengths& lambda) {
  const auto& X = cie::X();
  const auto& Y = cie::Y();
  const auto& Z = cie::Z();
  const auto& pdf = lambda.pdf();
  double x = 0, y = 0, z = 0;
  for (int i = 0; i < kNumWavelengths; ++i) {
    if (pdf[i] == 0.0f) continue;
    double w = double(L[i]) / double(pdf[i]);
    x += w * X(lambda[i]);
    y += w * Y(lambda[i]);
    z += w * Z(lambda[i]);
  }
  double norm = 1.0 / (kNumWavelengths * cie::yIntegral());
  return Vec3(float(x * norm), float(y * norm), float(z * norm));
}

}  // namespace inim
