#include "camera/sensor.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/output_file.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

constexpr int kL0 = 360, kL1 = 830;  // 1 nm grid, inclusive
constexpr int kN = kL1 - kL0 + 1;

std::vector<double> sampled(const Spectrum& s) {
  std::vector<double> v(kN);
  for (int i = 0; i < kN; ++i) v[size_t(i)] = s(float(kL0 + i));
  return v;
}

// Trapezoid integral of the product of two sampled spectra (and a third).
double dot3(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c) {
  double s = 0.0;
  for (int i = 0; i < kN; ++i) {
    double w = (i == 0 || i == kN - 1) ? 0.5 : 1.0;
    s += w * a[size_t(i)] * b[size_t(i)] * c[size_t(i)];
  }
  return s;
}

// D65 scaled to luminance Y = 1 (Y = integral(s ybar) / integral(ybar)).
const std::vector<double>& d65Unit() {
  static const std::vector<double> d = [] {
    std::vector<double> v = sampled(cie::D65());
    std::vector<double> one(kN, 1.0);
    std::vector<double> yb = sampled(cie::Y());
    double y = dot3(v, yb, one) / dot3(yb, one, one);
    for (auto& x : v) x /= y;
    return v;
  }();
  return d;
}

// Solves the 4x4 system A x = b by Gaussian elimination with partial pivoting.
void solve4(double A[4][5], double x[4]) {
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(A[r][c]) > std::abs(A[p][c])) p = r;
    for (int k = 0; k < 5; ++k) std::swap(A[c][k], A[p][k]);
    for (int r = c + 1; r < 4; ++r) {
      double f = A[r][c] / A[c][c];
      for (int k = c; k < 5; ++k) A[r][k] -= f * A[c][k];
    }
  }
  for (int r = 3; r >= 0; --r) {
    double s = A[r][4];
    for (int k = r + 1; k < 4; ++k) s -= A[r][k] * x[k];
    x[r] = s / A[r][r];
  }
}

}  // namespace

std::vector<std::vector<double>> colorTrainingReflectances() {
  std::vector<std::vector<double>> set;
  auto add = [&](auto f) {
    std::vector<double> v(kN);
    for (int i = 0; i < kN; ++i) v[size_t(i)] = f(double(kL0 + i));
    set.push_back(std::move(v));
  };
  for (double g : {0.05, 0.2, 0.5, 0.9}) add([g](double) { return g; });
  const double fwhmToSigma = 1.0 / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  for (double fwhm : {40.0, 100.0})
    for (double c = 400.0; c <= 700.0; c += 25.0) {
      const double s = fwhm * fwhmToSigma;
      add([=](double l) { return 0.05 + 0.85 * std::exp(-0.5 * (l - c) * (l - c) / (s * s)); });
    }
  for (double c = 400.0; c <= 700.0; c += 25.0) {
    const double s = 80.0 * fwhmToSigma;
    add([=](double l) { return 0.9 - 0.8 * std::exp(-0.5 * (l - c) * (l - c) / (s * s)); });
  }
  for (double c = 425.0; c <= 675.0; c += 25.0) {
    add([=](double l) { return 0.05 + 0.85 / (1.0 + std::exp(-(l - c) / 12.0)); });  // long-pass
    add([=](double l) { return 0.05 + 0.85 / (1.0 + std::exp((l - c) / 12.0)); });   // short-pass
  }
  return set;
}

ColorFit fitCameraRgbToXyz(const Spectrum& r, const Spectrum& g, const Spectrum& b) {
  const std::vector<double> sens[3] = {sampled(r), sampled(g), sampled(b)};
  const std::vector<double> cmf[3] = {sampled(cie::X()), sampled(cie::Y()), sampled(cie::Z())};
  const std::vector<double>& ill = d65Unit();
  const std::vector<double> one(kN, 1.0);
  const double yInt = dot3(cmf[1], one, one);

  ColorFit fit;
  for (int k = 0; k < 3; ++k) {
    const double raw = dot3(ill, sens[k], one);
    if (!(raw > 0.0)) throw InputError("", "spectral_sensitivity", "channel " + std::to_string(k),
                                       "a sensitivity with a non-zero response to D65");
    fit.whiteBalance[k] = 1.0 / raw;
    fit.whiteXyz[k] = dot3(ill, cmf[k], one) / yInt;
  }
  // Camera RGB (balanced) and XYZ of every training reflectance under D65 (Y = 1).
  const auto train = colorTrainingReflectances();
  std::vector<Vec3d> c, t;
  for (const auto& refl : train) {
    Vec3d ci, ti;
    for (int k = 0; k < 3; ++k) {
      ci[k] = dot3(refl, ill, sens[k]) * fit.whiteBalance[k];
      ti[k] = dot3(refl, ill, cmf[k]) / yInt;
    }
    c.push_back(ci);
    t.push_back(ti);
  }
  // Row by row: minimise sum (m . c_i - t_ij)^2 subject to m . (1,1,1) = whiteXyz_j.
  glm::dmat3 M(0.0);
  for (int row = 0; row < 3; ++row) {
    double A[4][5] = {};
    for (size_t i = 0; i < c.size(); ++i)
      for (int p = 0; p < 3; ++p) {
        for (int q = 0; q < 3; ++q) A[p][q] += 2.0 * c[i][p] * c[i][q];
        A[p][4] += 2.0 * c[i][p] * t[i][row];
      }
    for (int p = 0; p < 3; ++p) {
      A[p][3] = 1.0;
      A[3][p] = 1.0;
    }
    A[3][3] = 0.0;
    A[3][4] = fit.whiteXyz[row];
    double x[4];
    solve4(A, x);
    for (int q = 0; q < 3; ++q) M[q][row] = x[q];  // glm: M[column][row]
  }
  fit.cameraToXyz = M;
  fit.trainingSpectra = int(train.size());
  double sumDe = 0.0, sumSq = 0.0;
  for (size_t i = 0; i < c.size(); ++i) {
    const Vec3d est = M * c[i];
    const double de = ciede2000(xyzToLab(est, fit.whiteXyz), xyzToLab(t[i], fit.whiteXyz));
    sumDe += de;
    fit.maxDeltaE00 = std::max(fit.maxDeltaE00, de);
    const Vec3d d = est - t[i];
    sumSq += glm::dot(d, d);
  }
  fit.meanDeltaE00 = sumDe / double(c.size());
  fit.rmsXyz = std::sqrt(sumSq / double(3 * c.size()));
  return fit;
}

CameraSensor::CameraSensor(std::string name, SensorGeometry geometry, SpectrumPtr r, SpectrumPtr g, SpectrumPtr b,
                           std::string source)
    : name_(std::move(name)), source_(std::move(source)), geometry_(geometry), r_(std::move(r)), g_(std::move(g)),
      b_(std::move(b)) {
  if (r_ && g_ && b_) fit_ = fitCameraRgbToXyz(*r_, *g_, *b_);
}

Vec3d CameraSensor::rawResponse(double l) const {
  if (!r_) return Vec3d(0.0);
  const float lf = float(l);
  return {(*r_)(lf), (*g_)(lf), (*b_)(lf)};
}

Vec3d CameraSensor::cameraRgb(const Spectrum& radiance) const {
  if (!r_) return Vec3d(0.0);
  const std::vector<double> L = sampled(radiance), one(kN, 1.0);
  return Vec3d(dot3(L, sampled(*r_), one), dot3(L, sampled(*g_), one), dot3(L, sampled(*b_), one)) *
         fit_.whiteBalance;
}

CameraSensor parseSensor(const JsonObject& o) {
  SensorGeometry g;
  std::string name = o.string("name", "sensor");
  g.widthPx = o.integer("width_px", 1, std::numeric_limits<int>::max());
  g.heightPx = o.integer("height_px", 1, std::numeric_limits<int>::max());
  g.pitchMm = o.positive("pixel_pitch_mm");
  std::vector<std::string> channels = {"r", "g", "b"};
  if (o.has("channels")) {
    const Json& c = o.raw("channels");
    if (!c.is_array() || c.size() != 3 || !c[0].is_string() || !c[1].is_string() || !c[2].is_string())
      o.fail("channels", jsonValueText(c), "an array of 3 column names");
    for (int k = 0; k < 3; ++k) channels[size_t(k)] = c[size_t(k)].get<std::string>();
  }
  SpectrumPtr r, gg, b;
  std::string source;
  if (o.has("spectral_sensitivity")) {
    std::string rel = o.string("spectral_sensitivity");
    std::string path = o.path("spectral_sensitivity");
    if (!fs::exists(path)) path = dataPath(rel);
    if (!fs::exists(path))
      o.fail("spectral_sensitivity", "\"" + rel + "\"",
             "a CSV file relative to the camera file or the data folder (not found)");
    std::shared_ptr<PiecewiseLinearSpectrum> c[3];
    for (int k = 0; k < 3; ++k) {
      try {
        c[k] = loadSpectrumCSV(path, channels[size_t(k)]);
      } catch (const InputError& e) {
        throw InputError(o.file(), o.keyPath("spectral_sensitivity"), "\"" + rel + "\"",
                         "a sensitivity CSV with columns " + channels[0] + "," + channels[1] + "," + channels[2] +
                             " (" + e.what() + ")");
      }
    }
    r = c[0];
    gg = c[1];
    b = c[2];
    source = rel;
  }
  o.rejectUnknown();
  return CameraSensor(name, g, r, gg, b, source);
}

}  // namespace inim
