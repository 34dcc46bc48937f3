#include "analysis/depth_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/metrics.h"
#include "core/error.h"
#include "core/format.h"

namespace inim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void checkInputs(const Image& ref, const Image& rec, const DepthMap& depth, const PixelMask* mask,
                 const DepthBinning& b, const std::vector<float>* de) {
  requireSameSize(ref, rec, "reference", "reconstruction");
  const size_t n = size_t(ref.width) * size_t(ref.height);
  auto sized = [&](size_t got, const char* key) {
    if (got != n)
      throw InputError("", key, std::to_string(got) + " values", std::to_string(n) + " (one per pixel)");
  };
  sized(depth.z.size(), "depth");
  sized(depth.coverage.size(), "coverage");
  if (!depth.spread.empty()) sized(depth.spread.size(), "depth_spread");
  if (de) sized(de->size(), "delta_e");
  if (mask && (mask->width != ref.width || mask->height != ref.height))
    throw InputError(mask->source, "mask", std::to_string(mask->width) + "x" + std::to_string(mask->height),
                     "the images' size " + std::to_string(ref.width) + "x" + std::to_string(ref.height));
  if (b.count < 1) throw InputError("", "depth_bins", std::to_string(b.count), "a whole number >= 1");
  if (b.minZ && b.maxZ && !(*b.minZ < *b.maxZ))
    throw InputError("", "depth_range", "[" + formatNumber(*b.minZ) + ", " + formatNumber(*b.maxZ) + "]",
                     "min z < max z");
}

// The pixels that count: in the mask, covered, with a finite z.
std::vector<size_t> countedPixels(const Image& ref, const std::vector<float>& z, const std::vector<float>& a,
                                  const PixelMask* mask, double minCoverage) {
  std::vector<size_t> out;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      const size_t i = size_t(y) * size_t(ref.width) + size_t(x);
      if ((!mask || mask->counts(x, y)) && a[i] >= minCoverage && std::isfinite(z[i])) out.push_back(i);
    }
  return out;
}

// [lo, hi]: the given values, else the 1st and 99th percentiles; widened when flat.
std::pair<double, double> depthRange(const std::vector<size_t>& pixels, const std::vector<float>& z,
                                     const DepthBinning& b) {
  std::vector<double> zs;
  if (!b.minZ || !b.maxZ) {
    zs.reserve(pixels.size());
    for (size_t i : pixels) zs.push_back(z[i]);
  }
  double lo = b.minZ ? *b.minZ : percentile(zs, 1.0);
  double hi = b.maxZ ? *b.maxZ : percentile(zs, 99.0);
  if (!(hi > lo)) {
    const double c = b.minZ ? lo : hi;  // the value given, or the flat scene's z
    lo = c - 0.5, hi = c + 0.5;
  }
  return {lo, hi};
}

struct BinSums {
  int64_t pixels = 0, mixed = 0;
  double diff2 = 0.0, ref2 = 0.0, de = 0.0;
  double ref[3] = {0.0, 0.0, 0.0};  // per channel, for the mean colour
};

// sqrt(mean |ref - mean ref|^2) = sqrt(mean |ref|^2 - |mean ref|^2); NaN when that is lost in
// rounding (a flat bin: no detail to measure the error against).
double detailRms(const BinSums& s) {
  const double n = double(s.pixels), meanSq = s.ref2 / n;
  double meanColourSq = 0.0;
  for (double c : s.ref) meanColourSq += (c / n) * (c / n);
  const double var = meanSq - meanColourSq;
  return var > 1e-9 * meanSq ? std::sqrt(var) : kNaN;
}

}  // namespace

std::vector<DepthBin> errorVsDepth(const Image& reference, const Image& reconstruction, const DepthMap& depth,
                                   const PixelMask* mask, const DepthBinning& b, const std::vector<float>* deltaE) {
  checkInputs(reference, reconstruction, depth, mask, b, deltaE);
  const std::vector<size_t> pixels = countedPixels(reference, depth.z, depth.coverage, mask, b.minCoverage);
  if (pixels.empty()) return {};
  const auto [lo, hi] = depthRange(pixels, depth.z, b);
  const std::vector<float> ref = colorValues(reference, "reference"), rec = colorValues(reconstruction, "reconstruction");
  std::vector<float> ownDe;
  if (!deltaE) ownDe = deltaE2000Map(reference, reconstruction);
  const std::vector<float>& de = deltaE ? *deltaE : ownDe;

  const double width = (hi - lo) / double(b.count);
  std::vector<BinSums> sums(size_t(b.count));
  for (size_t i : pixels) {
    const double z = depth.z[i];
    if (z < lo || z > hi) continue;
    BinSums& s = sums[size_t(std::min(b.count - 1, int((z - lo) / width)))];
    if (b.leaveOutMixed && !depth.spread.empty() && depth.spread[i] > width) {
      ++s.mixed;
      continue;
    }
    ++s.pixels;
    for (int c = 0; c < 3; ++c) {
      const double r = ref[3 * i + size_t(c)], d = double(rec[3 * i + size_t(c)]) - r;
      s.diff2 += d * d;
      s.ref2 += r * r;
      s.ref[c] += r;
    }
    s.de += de[i];
  }

  std::vector<DepthBin> bins(size_t(b.count));
  for (int k = 0; k < b.count; ++k) {
    DepthBin& o = bins[size_t(k)];
    const BinSums& s = sums[size_t(k)];
    o.zLo = lo + k * width;
    o.zHi = k + 1 == b.count ? hi : lo + (k + 1) * width;
    o.zCentre = 0.5 * (o.zLo + o.zHi);
    o.pixels = s.pixels;
    o.mixedPixels = s.mixed;
    const bool enough = s.pixels >= std::max<int64_t>(1, b.minPixels);
    o.relRmse = enough && s.ref2 > 0.0 ? std::sqrt(s.diff2 / s.ref2) : kNaN;  // the means' 1/n cancels
    o.de2000Mean = enough ? s.de / double(s.pixels) : kNaN;
    o.errorOverDetail = enough ? std::sqrt(s.diff2 / double(s.pixels)) / detailRms(s) : kNaN;
  }
  return bins;
}

namespace {

// The same bins: equal z ranges (to rounding) and equal pixel counts.
bool sameBins(const std::vector<DepthBin>& a, const std::vector<DepthBin>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k) {
    const double tol = 1e-9 * std::max({1.0, std::abs(a[k].zLo), std::abs(a[k].zHi)});
    if (std::abs(a[k].zLo - b[k].zLo) > tol || std::abs(a[k].zHi - b[k].zHi) > tol || a[k].pixels != b[k].pixels)
      return false;
  }
  return true;
}

}  // namespace

std::vector<std::vector<double>> errorRelativeToLowest(const std::vector<std::vector<DepthBin>>& curves) {
  for (size_t i = 1; i < curves.size(); ++i)
    if (!sameBins(curves.front(), curves[i]))
      throw InputError("", "depth_bins", "curve " + std::to_string(i) + "'s bins",
                       "the same z ranges and pixels as curve 0's (one reference and mask)");
  std::vector<std::vector<double>> out(curves.size());
  if (curves.empty()) return out;
  for (size_t k = 0; k < curves.front().size(); ++k) {
    // Over the same pixels of the same reference, relative RMSEs are in the ratio of the RMSEs.
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& c : curves)
      if (std::isfinite(c[k].relRmse)) lowest = std::min(lowest, c[k].relRmse);
    for (size_t i = 0; i < curves.size(); ++i) {
      const double v = curves[i][k].relRmse;
      double r = kNaN;
      if (std::isfinite(v)) r = lowest > 0.0 ? v / lowest : (v == 0.0 ? 1.0 : std::numeric_limits<double>::infinity());
      out[i].push_back(r);
    }
  }
  return out;
}

Json depthBinsJson(const std::vector<DepthBin>& bins) {
  auto num = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json a = Json::array();
  for (const DepthBin& b : bins)
    a.push_back({{"z_lo", b.zLo},
                 {"z_hi", b.zHi},
                 {"pixels", b.pixels},
                 {"mixed_pixels", b.mixedPixels},
                 {"rel_rmse", num(b.relRmse)},
                 {"de2000_mean", num(b.de2000Mean)},
                 {"error_over_detail", num(b.errorOverDetail)}});
  return a;
}

std::vector<std::string> depthBinsCsvHeader() {
  return {"z_lo_mm", "z_hi_mm", "z_centre_mm", "pixels", "mixed_pixels", "rel_rmse", "de2000_mean", "error_over_detail"};
}

std::vector<std::vector<std::string>> depthBinsCsvRows(const std::vector<DepthBin>& bins) {
  std::vector<std::vector<std::string>> rows;
  for (const DepthBin& b : bins)
    rows.push_back({csvNumber(b.zLo), csvNumber(b.zHi), csvNumber(b.zCentre), std::to_string(b.pixels),
                    std::to_string(b.mixedPixels), csvNumber(b.relRmse), csvNumber(b.de2000Mean),
                    csvNumber(b.errorOverDetail)});
  return rows;
}

}  // namespace inim
