#pragma once
// RGB -> spectrum by the sigmoid-polynomial method of Jakob & Hanika 2019 ("A Low-
// Dimensional Function Space for Efficient Spectral Upsampling"): s(l) = sigmoid(c0 l^2 +
// c1 l + c2), with (c0,c1,c2) fitted per RGB so the spectrum under the colour space's
// whitepoint illuminant reproduces the RGB. The coefficient table is optimised on first
// use and cached on disk.
#include <memory>
#include <string>

#include "core/geometry.h"
#include "spectral/spectrum.h"

namespace inim {

struct SigmoidPolynomial {
  float c0 = 0, c1 = 0, c2 = 0;
  float operator()(float lambdaNm) const;
  float maxValue() const;
};

class RGBToSpectrumTable {
 public:
  // Table for linear Rec.709 / sRGB primaries under D65 (the project's working space).
  static const RGBToSpectrumTable& rec709();
  SigmoidPolynomial operator()(const Vec3& rgb) const;  // rgb in [0,1]
};

// A reflectance in [0,1] reproducing rgb (clamped to [0,1]) under D65.
class RGBAlbedoSpectrum final : public Spectrum {
 public:
  explicit RGBAlbedoSpectrum(const Vec3& rgb);
  float operator()(float l) const override { return rsp_(l); }
  float maxValue() const override { return rsp_.maxValue(); }

 private:
  SigmoidPolynomial rsp_;
};

// An unbounded spectrum (any non-negative rgb): scale * sigmoid spectrum.
class RGBUnboundedSpectrum final : public Spectrum {
 public:
  explicit RGBUnboundedSpectrum(const Vec3& rgb);
  float operator()(float l) const override { return scale_ * rsp_(l); }
  float maxValue() const override { return scale_ * rsp_.maxValue(); }

 private:
  float scale_ = 0;
  SigmoidPolynomial rsp_;
};

// An emission spectrum: the unbounded spectrum times the colour space's illuminant (D65),
// so that rgb = (1,1,1) is D65 with luminance Y = 1.
class RGBIlluminantSpectrum final : public Spectrum {
 public:
  explicit RGBIlluminantSpectrum(const Vec3& rgb);
  float operator()(float l) const override;
  float maxValue() const override;

 private:
  float scale_ = 0;
  SigmoidPolynomial rsp_;
};

}  // namespace inim
