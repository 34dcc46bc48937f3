#include "spectral/rgb_to_spectrum.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>

#include "core/content_hash.h"
#include "core/input_file.h"
#include "spectral/cie.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

float sigmoid(float x) {
  if (std::isinf(x)) return x > 0 ? 1.0f : 0.0f;
  return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
}

// ------------------------------------------------------------------------------------
// Optimisation of the sigmoid-polynomial coefficients (Jakob & Hanika 2019, after their
// rgb2spec_opt.cpp): Gauss-Newton on the CIELAB difference between the target rgb and the
// rgb of sigmoid(c0 t^2 + c1 t + c2) (t = normalised wavelength in [0,1]) as a reflectance
// under D65. Integrals use the same 1 nm trapezoid rule as reflectanceToXYZ(), so the
// table reproduces exactly what the rest of the code computes. The Jacobian is analytic.

using Mat = std::array<std::array<double, 3>, 3>;  // [row][col]

struct FitContext {
  static constexpr int kN = int(kLambdaMax - kLambdaMin) + 1;  // 471 samples, 1 nm
  std::array<double, kN> t{};                                   // normalised wavelength
  std::array<std::array<double, kN>, 3> tbl{};                  // weight * D65 * (M cmf)
  Mat rgbToXyz{};
  std::array<double, 3> white{};  // XYZ of D65 with Y = 1
  uint64_t hash = 0;              // of the tables, to validate the cache

  FitContext() {
    // Linear Rec.709 <-> XYZ (D65 xy = 0.3127, 0.3290), as ColorSystem::rec709ToXYZ.
    const double prim[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    const double wx = 0.3127, wy = 0.3290;
    Mat P{};
    for (int c = 0; c < 3; ++c) {
      P[0][c] = prim[c][0] / prim[c][1];
      P[1][c] = 1.0;
      P[2][c] = (1.0 - prim[c][0] - prim[c][1]) / prim[c][1];
    }
    Mat Pi = inverse(P);
    double W[3] = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
    for (int c = 0; c < 3; ++c) {
      double S = Pi[c][0] * W[0] + Pi[c][1] * W[1] + Pi[c][2] * W[2];
      for (int r = 0; r < 3; ++r) rgbToXyz[r][c] = P[r][c] * S;
    }
    Mat xyzToRgb = inverse(rgbToXyz);

    const auto& X = cie::X();
    const auto& Y = cie::Y();
    const auto& Z = cie::Z();
    const auto& D = cie::D65();
    double normY = 0.0;
    std::array<std::array<double, 3>, kN> xyzw{};
    for (int i = 0; i < kN; ++i) {
      float l = kLambdaMin + float(i);
      t[i] = (double(l) - kLambdaMin) / (double(kLambdaMax) - kLambdaMin);
      double w = (i == 0 || i == kN - 1) ? 0.5 : 1.0;
      double I = double(D(l)) * w;
      xyzw[i] = {X(l) * I, Y(l) * I, Z(l) * I};
      normY += xyzw[i][1];
    }
    for (int i = 0; i < kN; ++i) {
      for (int k = 0; k < 3; ++k) {
        white[k] += xyzw[i][k] / normY;
        double v = 0.0;
        for (int j = 0; j < 3; ++j) v += xyzToRgb[k][j] * xyzw[i][j] / normY;
        tbl[k][i] = v;
      }
    }
    // FNV-1a over the tables as floats.
    hash = 1469598103934665603ull;
    auto mix = [this](const void* p, size_t n) {
      const unsigned char* b = static_cast<const unsigned char*>(p);
      for (size_t i = 0; i < n; ++i) hash = (hash ^ b[i]) * 1099511628211ull;
    };
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < kN; ++i) {
        float f = float(tbl[k][i]);
        mix(&f, sizeof f);
      }
  }

  static Mat inverse(const Mat& m) {
    double a = m[0][0], b = m[0][1], c = m[0][2], d = m[1][0], e = m[1][1], f = m[1][2],
           g = m[2][0], h = m[2][1], k = m[2][2];
    double A = e * k - f * h, B = -(d * k - f * g), C = d * h - e * g;
    double det = a * A + b * B + c * C;
    Mat r{};
    r[0] = {A / det, -(b * k - c * h) / det, (b * f - c * e) / det};
    r[1] = {B / det, (a * k - c * g) / det, -(a * f - c * d) / det};
    r[2] = {C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
    return r;
  }

  // CIELAB of a linear rgb, and optionally d(Lab)/d(rgb).
  void lab(const double rgb[3], double out[3], Mat* J) const {
    double xyz[3];
    for (int r = 0; r < 3; ++r)
      xyz[r] = rgbToXyz[r][0] * rgb[0] + rgbToXyz[r][1] * rgb[1] + rgbToXyz[r][2] * rgb[2];
    constexpr double d = 6.0 / 29.0, d3 = d * d * d, k = 1.0 / (3.0 * d * d);
    double f[3], df[3];
    for (int i = 0; i < 3; ++i) {
      double v = xyz[i] / white[i];
      if (v > d3) {
        f[i] = std::cbrt(v);
        df[i] = 1.0 / (3.0 * f[i] * f[i] * white[i]);
      } else {
        f[i] = v * k + 4.0 / 29.0;
        df[i] = k / white[i];
      }
    }
    out[0] = 116.0 * f[1] - 16.0;
    out[1] = 500.0 * (f[0] - f[1]);
    out[2] = 200.0 * (f[1] - f[2]);
    if (J) {
      Mat dLdX = {{{0.0, 116.0 * df[1], 0.0},
                   {500.0 * df[0], -500.0 * df[1], 0.0},
                   {0.0, 200.0 * df[1], -200.0 * df[2]}}};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          (*J)[r][c] = dLdX[r][0] * rgbToXyz[0][c] + dLdX[r][1] * rgbToXyz[1][c] +
                       dLdX[r][2] * rgbToXyz[2][c];
    }
  }

  // rgb of the sigmoid spectrum with normalised coefficients c, and d(rgb)/dc.
  void spectrumRGB(const double c[3], double rgb[3], Mat* J) const {
    double o[3] = {0, 0, 0};
    Mat d{};
    for (int i = 0; i < kN; ++i) {
      double x = t[i];
      double p = (c[0] * x + c[1]) * x + c[2];
      double q = 1.0 + p * p;
      double sq = std::sqrt(q);
      double s = 0.5 + p / (2.0 * sq);
      double ds = 0.5 / (q * sq);
      for (int j = 0; j < 3; ++j) {
        double w = tbl[j][i];
        o[j] += w * s;
        if (J) {
          double g = w * ds;
          d[j][0] += g * x * x;
          d[j][1] += g * x;
          d[j][2] += g;
        }
      }
    }
    for (int j = 0; j < 3; ++j) rgb[j] = o[j];
    if (J) *J = d;
  }

  // Residual Lab(target) - Lab(spectrum) and its Jacobian with respect to c.
  void residual(const double c[3], const double targetLab[3], double res[3], Mat* J) const {
    double rgb[3], lab[3];
    Mat dRgb{}, dLab{};
    spectrumRGB(c, rgb, J ? &dRgb : nullptr);
    this->lab(rgb, lab, J ? &dLab : nullptr);
    for (int i = 0; i < 3; ++i) res[i] = targetLab[i] - lab[i];
    if (J)
      for (int r = 0; r < 3; ++r)
        for (int cc = 0; cc < 3; ++cc)
          (*J)[r][cc] = -(dLab[r][0] * dRgb[0][cc] + dLab[r][1] * dRgb[1][cc] +
                          dLab[r][2] * dRgb[2][cc]);
  }

  // Gauss-Newton from (and into) c; returns the final squared residual.
  double gaussNewton(const double rgb[3], double c[3], int iterations = 15) const {
    double target[3];
    lab(rgb, target, nullptr);
    double r2 = 0.0;
    for (int it = 0; it < iterations; ++it) {
      double res[3];
      Mat J{};
      residual(c, target, res, &J);
      r2 = res[0] * res[0] + res[1] * res[1] + res[2] * res[2];
      if (r2 < 1e-10) break;
      double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                   J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                   J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      if (!(std::abs(det) > 1e-15)) break;
      Mat Ji = inverse(J);
      for (int j = 0; j < 3; ++j) c[j] -= Ji[j][0] * res[0] + Ji[j][1] * res[1] + Ji[j][2] * res[2];
      double m = std::max({c[0], c[1], c[2]});
      if (m > 200.0)
        for (int j = 0; j < 3; ++j) c[j] *= 200.0 / m;
    }
    return r2;
  }

  // Normalised-wavelength coefficients -> coefficients in nm.
  static SigmoidPolynomial toNm(const double c[3]) {
    const double l0 = kLambdaMin, s = 1.0 / (double(kLambdaMax) - kLambdaMin);
    SigmoidPolynomial p;
    p.c0 = float(c[0] * s * s);
    p.c1 = float(c[1] * s - 2.0 * c[0] * l0 * s * s);
    p.c2 = float(c[2] - c[1] * l0 * s + c[0] * (l0 * s) * (l0 * s));
    return p;
  }
};

const FitContext& fitContext() {
  static const FitContext ctx;
  return ctx;
}

double smoothstep(double x) { return x * x * (3.0 - 2.0 * x); }

constexpr char kMagic[8] = {'I', 'N', 'I', 'M', 'R', '2', 'S', '1'};
constexpr uint32_t kFormatVersion = 1;

std::string cacheName(int res) { return "rgb2spec_rec709_" + std::to_string(res) + ".bin"; }

}  // namespace

// ------------------------------------------------------------------------------------

float SigmoidPolynomial::operator()(float l) const { return sigmoid((c0 * l + c1) * l + c2); }

float SigmoidPolynomial::maxValue() const {
  float r = std::max((*this)(kLambdaMin), (*this)(kLambdaMax));
  if (c0 < 0.0f) {
    float lm = -c1 / (2.0f * c0);
    if (lm >= kLambdaMin && lm <= kLambdaMax) r = std::max(r, (*this)(lm));
  }
  return r;
}

SigmoidPolynomial RGBToSpectrumTable::fit(const Vec3& rgbIn) {
  Vec3 rgb;
  for (int i = 0; i < 3; ++i)
    rgb[i] = std::isnan(rgbIn[i]) ? 0.0f : std::clamp(rgbIn[i], 0.0f, 1.0f);
  if (rgb.x == rgb.y && rgb.y == rgb.z) {
    SigmoidPolynomial p;
    p.c2 = (rgb.x - 0.5f) / std::sqrt(rgb.x * (1.0f - rgb.x));
    return p;
  }
  const FitContext& ctx = fitContext();
  double m = maxComponent(rgb);
  // Continuation along brightness from a dim colour of the same chromaticity, as the
  // table build does, so Gauss-Newton starts near the solution.
  double c[3] = {0, 0, 0};
  const int steps = 24;
  double b0 = std::min(m, 0.03);
  for (int s = 0; s <= steps; ++s) {
    double b = b0 + (m - b0) * double(s) / steps;
    double v[3] = {rgb.x / m * b, rgb.y / m * b, rgb.z / m * b};
    ctx.gaussNewton(v, c);
  }
  return FitContext::toNm(c);
}

RGBToSpectrumTable RGBToSpectrumTable::compute(int res) {
  if (res < 4) res = 4;
  auto t0 = std::chrono::steady_clock::now();
  const FitContext& ctx = fitContext();
  RGBToSpectrumTable t;
  t.res_ = res;
  t.zNodes_.resize(res);
  for (int k = 0; k < res; ++k) t.zNodes_[k] = float(smoothstep(smoothstep(k / double(res - 1))));
  t.coeffs_.assign(size_t(3) * res * res * res * 3, 0.0f);
  // Isolated, so a caller inside an outer TBB loop never runs outer tasks while it waits
  // (which could re-enter the static initialisation of rec709()).
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(0, 3 * res, [&](int task) {
      const int l = task / res, j = task % res;
      const double y = j / double(res - 1);
      for (int i = 0; i < res; ++i) {
        const double x = i / double(res - 1);
        auto solve = [&](int k, double c[3]) {
          double b = t.zNodes_[k];
          double rgb[3];
          rgb[l] = b;
          rgb[(l + 1) % 3] = x * b;
          rgb[(l + 2) % 3] = y * b;
          ctx.gaussNewton(rgb, c);
          SigmoidPolynomial p = FitContext::toNm(c);
          size_t idx = ((size_t(l) * res + k) * res + j) * res + i;
          t.coeffs_[3 * idx + 0] = p.c0;
          t.coeffs_[3 * idx + 1] = p.c1;
          t.coeffs_[3 * idx + 2] = p.c2;
        };
        const int start = res / 5;
        double c[3] = {0, 0, 0};
        for (int k = start; k < res; ++k) solve(k, c);
        c[0] = c[1] = c[2] = 0;
        for (int k = start; k >= 0; --k) solve(k, c);
      }
    });
  });
  t.buildSeconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

std::string RGBToSpectrumTable::cachePath(int res) {
  return (fs::path(cacheDirs().front()) / cacheName(res)).string();
}

bool RGBToSpectrumTable::readCache(const std::string& path, int res) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char magic[8];
  uint32_t version = 0, r = 0;
  uint64_t hash = 0;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(&version), sizeof version);
  in.read(reinterpret_cast<char*>(&r), sizeof r);
  in.read(reinterpret_cast<char*>(&hash), sizeof hash);
  if (!in || std::memcmp(magic, kMagic, 8) != 0 || version != kFormatVersion ||
      r != uint32_t(res) || hash != fitContext().hash)
    return false;
  std::vector<float> z(res), c(size_t(3) * res * res * res * 3);
  in.read(reinterpret_cast<char*>(z.data()), std::streamsize(z.size() * sizeof(float)));
  in.read(reinterpret_cast<char*>(c.data()), std::streamsize(c.size() * sizeof(float)));
  if (!in || in.peek() != std::char_traits<char>::eof()) return false;
  for (float v : c)
    if (!std::isfinite(v)) return false;
  for (int k = 0; k < res; ++k)
    if (!(z[k] >= 0.0f && z[k] <= 1.0f) || (k > 0 && !(z[k] > z[k - 1]))) return false;
  res_ = res;
  zNodes_ = std::move(z);
  coeffs_ = std::move(c);
  fromCache_ = true;
  cacheFile_ = path;
  return true;
}

void RGBToSpectrumTable::writeCache(const std::string& path) const {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  std::random_device rd;
  std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(rd());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    uint32_t version = kFormatVersion, r = uint32_t(res_);
    uint64_t hash = fitContext().hash;
    out.write(kMagic, 8);
    out.write(reinterpret_cast<const char*>(&version), sizeof version);
    out.write(reinterpret_cast<const char*>(&r), sizeof r);
    out.write(reinterpret_cast<const char*>(&hash), sizeof hash);
    out.write(reinterpret_cast<const char*>(zNodes_.data()),
              std::streamsize(zNodes_.size() * sizeof(float)));
    out.write(reinterpret_cast<const char*>(coeffs_.data()),
              std::streamsize(coeffs_.size() * sizeof(float)));
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw std::runtime_error("cannot write " + tmp);
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot rename into " + path);
  }
}

RGBToSpectrumTable RGBToSpectrumTable::loadOrCompute(int res) {
  auto dirs = cacheDirs();
  for (const auto& d : dirs) {
    RGBToSpectrumTable t;
    if (t.readCache((fs::path(d) / cacheName(res)).string(), res)) return t;
  }
  std::cerr << "inim: optimising the RGB->spectrum table (" << res
            << "^3, once; cached afterwards)..." << std::endl;
  RGBToSpectrumTable t = compute(res);
  std::string where;
  for (const auto& d : dirs) {
    try {
      where = (fs::path(d) / cacheName(res)).string();
      t.writeCache(where);
      t.cacheFile_ = where;
      break;
    } catch (const std::exception&) {
    }
  }
  std::cerr << "inim: RGB->spectrum table took " << t.buildSeconds_ << " s"
            << (where.empty() ? std::string(" (could not cache it)") : ", cached at " + where)
            << std::endl;
  return t;
}

const RGBToSpectrumTable& RGBToSpectrumTable::rec709() {
  static const RGBToSpectrumTable t = loadOrCompute(kResolution);
  return t;
}

SigmoidPolynomial RGBToSpectrumTable::operator()(const Vec3& rgbIn) const {
  Vec3 rgb;
  for (int i = 0; i < 3; ++i)  // NaN -> 0, then clamp to [0,1]
    rgb[i] = std::isnan(rgbIn[i]) ? 0.0f : std::clamp(rgbIn[i], 0.0f, 1.0f);
  if (rgb.x == rgb.y && rgb.y == rgb.z) {
    SigmoidPolynomial p;
    p.c2 = (rgb.x - 0.5f) / std::sqrt(rgb.x * (1.0f - rgb.x));
    return p;
  }
  const int maxc = (rgb.x > rgb.y) ? (rgb.x > rgb.z ? 0 : 2) : (rgb.y > rgb.z ? 1 : 2);
  const float z = rgb[maxc];
  const int res = res_;
  const float x = rgb[(maxc + 1) % 3] * float(res - 1) / z;
  const float y = rgb[(maxc + 2) % 3] * float(res - 1) / z;
  const int xi = std::min(int(x), res - 2), yi = std::min(int(y), res - 2);
  int zi = int(std::upper_bound(zNodes_.begin(), zNodes_.end(), z) - zNodes_.begin()) - 1;
  zi = std::clamp(zi, 0, res - 2);
  const float dx = x - float(xi), dy = y - float(yi);
  const float dz = (z - zNodes_[zi]) / (zNodes_[zi + 1] - zNodes_[zi]);
  float c[3];
  for (int i = 0; i < 3; ++i) {
    auto co = [&](int ddz, int ddy, int ddx) {
      size_t idx = ((size_t(maxc) * res + zi + ddz) * res + yi + ddy) * res + xi + ddx;
      return coeffs_[3 * idx + i];
    };
    auto lerp = [](float t, float a, float b) { return (1.0f - t) * a + t * b; };
    c[i] = lerp(dz, lerp(dy, lerp(dx, co(0, 0, 0), co(0, 0, 1)), lerp(dx, co(0, 1, 0), co(0, 1, 1))),
                lerp(dy, lerp(dx, co(1, 0, 0), co(1, 0, 1)), lerp(dx, co(1, 1, 0), co(1, 1, 1))));
  }
  return SigmoidPolynomial{c[0], c[1], c[2]};
}

// ------------------------------------------------------------------------------------

namespace {
// Non-negative, finite rgb (NaN and negative -> 0, +inf -> largest float).
Vec3 sanitize(const Vec3& v) {
  Vec3 r;
  for (int i = 0; i < 3; ++i)
    r[i] = std::isnan(v[i]) ? 0.0f : std::clamp(v[i], 0.0f, std::numeric_limits<float>::max());
  return r;
}
}  // namespace

RGBAlbedoSpectrum::RGBAlbedoSpectrum(const Vec3& rgb) : rsp_(RGBToSpectrumTable::rec709()(rgb)) {}

RGBUnboundedSpectrum::RGBUnboundedSpectrum(const Vec3& rgbIn) {
  Vec3 rgb = sanitize(rgbIn);
  float m = maxComponent(rgb);
  scale_ = 2.0f * m;
  rsp_ = RGBToSpectrumTable::rec709()(scale_ > 0.0f ? rgb / scale_ : Vec3(0.0f));
}

namespace {
// 1 / Y of the tabulated D65, so D65 * d65Scale() has luminance Y = 1.
float d65Scale() {
  static const float s = float(1.0 / spectrumToXYZ(cie::D65()).y);
  return s;
}
}  // namespace

RGBIlluminantSpectrum::RGBIlluminantSpectrum(const Vec3& rgbIn) {
  Vec3 rgb = sanitize(rgbIn);
  float m = maxComponent(rgb);
  scale_ = 2.0f * m;
  rsp_ = RGBToSpectrumTable::rec709()(scale_ > 0.0f ? rgb / scale_ : Vec3(0.0f));
  d65Scale();
}

float RGBIlluminantSpectrum::operator()(float l) const {
  return scale_ * rsp_(l) * d65Scale() * cie::D65()(l);
}

float RGBIlluminantSpectrum::maxValue() const {
  return scale_ * rsp_.maxValue() * d65Scale() * cie::D65().maxValue();
}

}  // namespace inim
