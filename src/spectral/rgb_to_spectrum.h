#pragma once
// RGB -> spectrum by the sigmoid-polynomial method of Jakob & Hanika 2019 ("A Low-
// Dimensional Function Space for Efficient Spectral Upsampling"): s(l) = sigmoid(c0 l^2 +
// c1 l + c2), with (c0,c1,c2) fitted per RGB so the spectrum under the colour space's
// whitepoint illuminant reproduces the RGB. The coefficient table is optimised on first
// use and cached on disk.
#include <memory>
#include <string>
#include <vector>

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

  // Resolution of rec709(): 3 x res^3 coefficient triples.
  static constexpr int kResolution = 64;
  // Loads the table from the cache file, or optimises it (TBB) and writes the cache.
  static RGBToSpectrumTable loadOrCompute(int res);
  // Optimises the table now, without touching the cache.
  static RGBToSpectrumTable compute(int res);
  // Fits one rgb directly by Gauss-Newton (no table), for tests and one-off colours.
  static SigmoidPolynomial fit(const Vec3& rgb);
  // Cache file: $INIM_CACHE_DIR, else $XDG_CACHE_HOME/inim, else ~/.cache/inim, else the
  // temp folder; named rgb2spec_rec709_<res>.bin.
  static std::string cachePath(int res);

  int resolution() const { return res_; }
  bool loadedFromCache() const { return fromCache_; }
  double buildSeconds() const { return buildSeconds_; }  // optimisation time, 0 if cached
  const std::string& cacheFile() const { return cacheFile_; }  // read or written; "" if none

 private:
  RGBToSpectrumTable() = default;
  bool readCache(const std::string& path, int res);
  void writeCache(const std::string& path) const;
  int res_ = 0;
  std::vector<float> zNodes_;  // res brightness nodes, smoothstep(smoothstep(k/(res-1)))
  std::vector<float> coeffs_;  // [maxc][z][y][x][3], coefficients in nm
  bool fromCache_ = false;
  double buildSeconds_ = 0.0;
  std::string cacheFile_;
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
