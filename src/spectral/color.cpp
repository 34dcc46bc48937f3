#include "spectral/color.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <shared_mutex>
#include <stdexcept>

#include "core/error.h"
#include "core/output_file.h"
#include "core/parallel.h"

namespace OCIO = OCIO_NAMESPACE;

namespace inim {

struct ColorSystem::Cache {
  std::shared_mutex mutex;
  std::map<std::pair<std::string, std::string>, OCIO::ConstCPUProcessorRcPtr> processors;
};

namespace {
const OCIO::Config& asConfig(const std::shared_ptr<const void>& p) {
  return *static_cast<const OCIO::Config*>(p.get());
}
}  // namespace

ColorSystem::ColorSystem(std::string path) : path_(std::move(path)), cache_(std::make_shared<Cache>()) {
  OCIO::ConstConfigRcPtr cfg;
  try {
    cfg = OCIO::Config::CreateFromFile(path_.c_str());
    cfg->validate();
  } catch (const OCIO::Exception& e) {
    throw InputError(path_, "", e.what(), "a valid OpenColorIO 2.1 config");
  }
  config_ = std::shared_ptr<const void>(cfg, cfg.get());
}

const ColorSystem& ColorSystem::instance() {
  static const ColorSystem cs([] {
    if (const char* env = std::getenv("OCIO"); env && *env) return std::string(env);
    return dataPath("spectra/ocio/config.ocio");
  }());
  return cs;
}

std::shared_ptr<const void> ColorSystem::cpuProcessor(const std::string& from,
                                                      const std::string& to) const {
  auto key = std::make_pair(from, to);
  {
    std::shared_lock<std::shared_mutex> lock(cache_->mutex);
    auto it = cache_->processors.find(key);
    if (it != cache_->processors.end())
      return std::shared_ptr<const void>(it->second, it->second.get());
  }
  std::unique_lock<std::shared_mutex> lock(cache_->mutex);
  auto it = cache_->processors.find(key);
  if (it == cache_->processors.end()) {
    const OCIO::Config& cfg = asConfig(config_);
    for (const std::string* name : {&from, &to})
      if (!cfg.getColorSpace(name->c_str())) {
        std::string known;
        for (int i = 0; i < cfg.getNumColorSpaces(); ++i)
          known += (i ? ", " : "") + std::string(cfg.getColorSpaceNameByIndex(i));
        throw InputError(path_, "colour space", *name, "one of " + known);
      }
    try {
      auto proc = cfg.getProcessor(from.c_str(), to.c_str());
      it = cache_->processors.emplace(key, proc->getDefaultCPUProcessor()).first;
    } catch (const OCIO::Exception& e) {
      throw InputError(path_, from + " -> " + to, e.what(), "a conversion the config supports");
    }
  }
  return std::shared_ptr<const void>(it->second, it->second.get());
}

Vec3 ColorSystem::convert(const Vec3& v, const std::string& from, const std::string& to) const {
  if (from == to) return v;
  auto p = cpuProcessor(from, to);
  float rgb[3] = {v.x, v.y, v.z};
  static_cast<const OCIO::CPUProcessor*>(p.get())->applyRGB(rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

void ColorSystem::convertImage(Image& img, const std::string& from, const std::string& to) const {
  if (from == to || img.width == 0 || img.height == 0) return;
  if (img.numChannels() < 3)
    throw std::invalid_argument("convertImage: image has fewer than 3 channels");
  auto p = cpuProcessor(from, to);
  const auto* processor = static_cast<const OCIO::CPUProcessor*>(p.get());
  const ptrdiff_t chan = sizeof(float);
  const ptrdiff_t px = chan * img.numChannels();
  // Bands of whole rows in parallel: OCIO converts each row alike wherever a band starts, so the
  // result is the same at any thread count.
  parallelForRange(
      img.height,
      [&](int64_t y0, int64_t y1) {
        float* first = img.data.data() + size_t(y0) * size_t(img.width) * size_t(img.numChannels());
        OCIO::PackedImageDesc desc(first, img.width, long(y1 - y0), 3, OCIO::BIT_DEPTH_F32, chan, px,
                                   px * img.width);
        processor->apply(desc);
      },
      nullptr, 16);
}

Mat3 rgbToXYZMatrix(const Vec2& r, const Vec2& g, const Vec2& b, const Vec2& white) {
  auto XYZ = [](const Vec2& c) {
    return glm::dvec3(double(c.x) / c.y, 1.0, (1.0 - c.x - c.y) / double(c.y));
  };
  glm::dmat3 P(XYZ(r), XYZ(g), XYZ(b));  // columns = primaries
  glm::dvec3 S = glm::inverse(P) * XYZ(white);
  glm::dmat3 M(P[0] * S.x, P[1] * S.y, P[2] * S.z);
  return Mat3(M);
}

namespace {
glm::dmat3 rec709ToXYZd() {
  auto XYZ = [](double x, double y) { return glm::dvec3(x / y, 1.0, (1.0 - x - y) / y); };
  glm::dmat3 P(XYZ(0.64, 0.33), XYZ(0.30, 0.60), XYZ(0.15, 0.06));
  glm::dvec3 S = glm::inverse(P) * XYZ(0.3127, 0.3290);
  return glm::dmat3(P[0] * S.x, P[1] * S.y, P[2] * S.z);
}
}  // namespace

Mat3 ColorSystem::rec709ToXYZ() { return Mat3(rec709ToXYZd()); }
Mat3 ColorSystem::xyzToRec709() { return Mat3(glm::inverse(rec709ToXYZd())); }

float srgbEncode(float x) {
  if (x <= 0.0031308f) return 12.92f * x;
  return 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}
float srgbDecode(float x) {
  if (x <= 0.04045f) return x / 12.92f;
  return std::pow((x + 0.055f) / 1.055f, 2.4f);
}

Vec3d xyzToLab(const Vec3d& xyz, const Vec3d& white) {
  auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  };
  double fx = f(xyz.x / white.x), fy = f(xyz.y / white.y), fz = f(xyz.z / white.z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// Sharma, Wu, Dalal (2005), "The CIEDE2000 color-difference formula: implementation notes,
// supplementary test data, and mathematical observations"; kL = kC = kH = 1.
double ciede2000(const Vec3d& lab1, const Vec3d& lab2) {
  constexpr double pi = 3.14159265358979323846;
  auto deg = [](double r) { return r * 180.0 / pi; };
  auto rad = [](double d) { return d * pi / 180.0; };
  const double L1 = lab1.x, a1 = lab1.y, b1 = lab1.z;
  const double L2 = lab2.x, a2 = lab2.y, b2 = lab2.z;
  const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2);
  const double Cbar = 0.5 * (C1 + C2);
  const double Cbar7 = std::pow(Cbar, 7.0);
  const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + std::pow(25.0, 7.0))));
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;
  const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
  auto hue = [&](double b, double ap) {
    if (b == 0.0 && ap == 0.0) return 0.0;
    double h = deg(std::atan2(b, ap));
    return h < 0.0 ? h + 360.0 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
  const double dLp = L2 - L1;
  const double dCp = C2p - C1p;
  double dhp = 0.0;
  if (C1p * C2p != 0.0) {
    dhp = h2p - h1p;
    if (dhp > 180.0) dhp -= 360.0;
    else if (dhp < -180.0) dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(rad(dhp / 2.0));
  const double Lbarp = 0.5 * (L1 + L2);
  const double Cbarp = 0.5 * (C1p + C2p);
  double hbarp = h1p + h2p;
  if (C1p * C2p != 0.0) {
    if (std::abs(h1p - h2p) <= 180.0) hbarp = 0.5 * (h1p + h2p);
    else if (h1p + h2p < 360.0) hbarp = 0.5 * (h1p + h2p + 360.0);
    else hbarp = 0.5 * (h1p + h2p - 360.0);
  }
  const double T = 1.0 - 0.17 * std::cos(rad(hbarp - 30.0)) + 0.24 * std::cos(rad(2.0 * hbarp)) +
                   0.32 * std::cos(rad(3.0 * hbarp + 6.0)) - 0.20 * std::cos(rad(4.0 * hbarp - 63.0));
  const double dTheta = 30.0 * std::exp(-std::pow((hbarp - 275.0) / 25.0, 2.0));
  const double Cbarp7 = std::pow(Cbarp, 7.0);
  const double RC = 2.0 * std::sqrt(Cbarp7 / (Cbarp7 + std::pow(25.0, 7.0)));
  const double Lm = (Lbarp - 50.0) * (Lbarp - 50.0);
  const double SL = 1.0 + 0.015 * Lm / std::sqrt(20.0 + Lm);
  const double SC = 1.0 + 0.045 * Cbarp;
  const double SH = 1.0 + 0.015 * Cbarp * T;
  const double RT = -std::sin(rad(2.0 * dTheta)) * RC;
  const double tL = dLp / SL, tC = dCp / SC, tH = dHp / SH;
  return std::sqrt(tL * tL + tC * tC + tH * tH + RT * tC * tH);
}

}  // namespace inim
