#include "scene/texture.h"

#include <algorithm>
#include <cmath>

#include "core/image.h"

namespace inim {

float srgbToLinear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

ReflectanceTexture ReflectanceTexture::constant(BakedSpectrum s) {
  ReflectanceTexture t;
  t.type_ = TextureType::Constant;
  t.a_ = std::move(s);
  return t;
}

ReflectanceTexture ReflectanceTexture::pattern(TextureType type, BakedSpectrum background,
                                               BakedSpectrum ink, const PatternParams& p) {
  ReflectanceTexture t;
  t.type_ = type;
  t.a_ = std::move(background);
  t.b_ = std::move(ink);
  t.p_ = p;
  return t;
}

ReflectanceTexture ReflectanceTexture::image(const Image& img, bool repeat) {
  ReflectanceTexture t;
  t.type_ = TextureType::Image;
  t.w_ = img.width;
  t.h_ = img.height;
  t.repeat_ = repeat;
  t.texels_.resize(size_t(img.width) * img.height);
  const RGBToSpectrumTable& table = RGBToSpectrumTable::rec709();
  int nc = img.numChannels();
  double sum = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      Vec3 rgb;
      for (int c = 0; c < 3; ++c) rgb[c] = img.at(x, y, nc >= 3 ? c : 0);
      rgb = glm::clamp(rgb, Vec3(0.0f), Vec3(1.0f));
      SigmoidPolynomial s = table(rgb);
      t.texels_[size_t(y) * img.width + x] = s;
      sum += (rgb.x + rgb.y + rgb.z) / 3.0;
      t.imageMax_ = std::max(t.imageMax_, s.maxValue());
    }
  t.imageMean_ = t.texels_.empty() ? 0.0f : float(sum / double(t.texels_.size()));
  return t;
}

namespace {

// A ruler along s with its baseline at t = 0 and ticks toward -t (dir = -1) or +t (dir = +1).
float rulerInk(float s, float t, float tick, float line, float dir) {
  float tt = t * dir;  // distance from the baseline along the tick direction
  if (tt < -0.5f * line) return 0.0f;
  if (tt <= 0.5f * line) return 1.0f;  // baseline
  float k = std::floor(s / tick + 0.5f);
  if (std::abs(s - k * tick) > 0.5f * line) return 0.0f;
  long ki = long(k);
  float len = (ki % 10 == 0) ? 6.0f * tick : (ki % 5 == 0 ? 4.0f * tick : 2.5f * tick);
  return tt <= len ? 1.0f : 0.0f;
}

float checkerInk(float s, float t, float period) {
  long i = long(std::floor(s / period)) + long(std::floor(t / period));
  return (i & 1) ? 1.0f : 0.0f;
}

float slantedInk(float s, float t, float angleDeg) {
  float a = radians(angleDeg);
  // Edge through the origin, tilted clockwise from vertical; ink on its left.
  return (s * std::cos(a) + t * std::sin(a)) < 0.0f ? 1.0f : 0.0f;
}

float starInk(float s, float t, int spokes, float radius) {
  float r2 = s * s + t * t;
  if (r2 > radius * radius) return 0.0f;
  float phi = std::atan2(t, s) + kPi;  // [0, 2pi]
  long k = long(std::floor(phi * float(spokes) / kPi));
  return (k & 1) ? 0.0f : 1.0f;
}

// The composite printed target of object 3: a frame, rulers along the top and bottom
// edges (1/5/10 mm ticks), a Siemens star at the left, a checkerboard in the middle and a
// slanted-edge square at the right.
float scaleTargetInk(float s, float t, const PatternParams& p) {
  float W = p.size_mm.x, H = p.size_mm.y, line = p.line_mm;
  float hw = 0.5f * W, hh = 0.5f * H;
  if (std::abs(s) > hw || std::abs(t) > hh) return 0.0f;
  // Frame.
  if (hw - std::abs(s) < line || hh - std::abs(t) < line) return 1.0f;
  float margin = 2.0f * line + 0.5f;
  // Rulers: ticks hang from a baseline just inside the top edge and rise from the bottom.
  float band = 6.5f * p.tick_mm;
  if (t > hh - margin - band) return rulerInk(s, t - (hh - margin), p.tick_mm, line, -1.0f);
  if (t < -hh + margin + band) return rulerInk(s, t - (-hh + margin), p.tick_mm, line, +1.0f);
  float inner = hh - margin - band - 1.0f;  // half-height of the middle band
  if (inner <= 0.0f) return 0.0f;
  float cell = std::min(inner, W / 6.0f - 1.0f);
  // Siemens star (left), checker (centre, whole squares), slanted edge (right, framed).
  float cx = W / 3.0f;
  if (std::abs(s + cx) <= cell && std::abs(t) <= cell)
    return starInk(s + cx, t, p.spokes, cell);
  float half = cell >= p.period_mm ? p.period_mm * std::floor(cell / p.period_mm) : cell;
  if (std::abs(s) <= half && std::abs(t) <= half) return checkerInk(s + half, t + half, p.period_mm);
  float ds = std::abs(s - cx), dt = std::abs(t);
  if (ds <= cell && dt <= cell) {
    if (cell - std::max(ds, dt) < line) return 1.0f;  // frame around the edge square
    return slantedInk(s - cx, t, p.angle_deg);
  }
  return 0.0f;
}

}  // namespace

float ReflectanceTexture::inkFraction(Vec2 st) const {
  float s = st.x - p_.center_mm.x, t = st.y - p_.center_mm.y;
  switch (type_) {
    case TextureType::Checker: return checkerInk(s, t, p_.period_mm);
    case TextureType::Ruler: return rulerInk(s, t, p_.tick_mm, p_.line_mm, -1.0f);
    case TextureType::SlantedEdge: return slantedInk(s, t, p_.angle_deg);
    case TextureType::SiemensStar: return starInk(s, t, p_.spokes, p_.radius_mm);
    case TextureType::ScaleTarget: return scaleTargetInk(s, t, p_);
    default: return 0.0f;
  }
}

SampledSpectrum ReflectanceTexture::evaluate(const SurfaceCoords& c,
                                             const SampledWavelengths& lambda) const {
  switch (type_) {
    case TextureType::Constant: return a_.sample(lambda);
    case TextureType::Image: {
      float x = c.uv.x * float(w_) - 0.5f, y = (1.0f - c.uv.y) * float(h_) - 0.5f;
      if (!std::isfinite(x) || !std::isfinite(y)) return SampledSpectrum(0.0f);
      float fx = std::floor(x), fy = std::floor(y);
      float ax = x - fx, ay = y - fy;
      int x0 = int(fx), y0 = int(fy);
      auto texel = [&](int xi, int yi) -> const SigmoidPolynomial& {
        if (repeat_) {
          xi %= w_; if (xi < 0) xi += w_;
          yi %= h_; if (yi < 0) yi += h_;
        } else {
          xi = std::clamp(xi, 0, w_ - 1);
          yi = std::clamp(yi, 0, h_ - 1);
        }
        return texels_[size_t(yi) * w_ + xi];
      };
      const SigmoidPolynomial &t00 = texel(x0, y0), &t10 = texel(x0 + 1, y0),
                              &t01 = texel(x0, y0 + 1), &t11 = texel(x0 + 1, y0 + 1);
      SampledSpectrum r;
      for (int i = 0; i < kNumWavelengths; ++i) {
        float l = lambda[i];
        r[i] = (1 - ax) * (1 - ay) * t00(l) + ax * (1 - ay) * t10(l) + (1 - ax) * ay * t01(l) +
               ax * ay * t11(l);
      }
      return r;
    }
    default: {
      float ink = inkFraction(c.st);
      if (ink <= 0.0f) return a_.sample(lambda);
      if (ink >= 1.0f) return b_.sample(lambda);
      return a_.sample(lambda) * (1.0f - ink) + b_.sample(lambda) * ink;
    }
  }
}

float ReflectanceTexture::averageAlbedo() const {
  switch (type_) {
    case TextureType::Constant: return a_.average();
    case TextureType::Image: return imageMean_;
    default: return 0.5f * (a_.average() + b_.average());
  }
}

float ReflectanceTexture::maxAlbedo() const {
  switch (type_) {
    case TextureType::Constant: return a_.maxValue();
    case TextureType::Image: return imageMax_;
    default: return std::max(a_.maxValue(), b_.maxValue());
  }
}

}  // namespace inim
