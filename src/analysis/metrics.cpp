#include "analysis/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/parallel.h"
#include "spectral/color.h"
#include "core/file_kinds.h"

namespace inim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string sizeText(int w, int h) { return std::to_string(w) + " x " + std::to_string(h); }

// Calls fn(y) for every row in parallel, fn returning a per-row double; returns the rows'
// values summed in row order (deterministic for any thread count).
template <class Fn>
std::vector<double> perRow(int height, Fn&& fn) {
  std::vector<double> rows(size_t(std::max(height, 0)), 0.0);
  parallelForRange(
      height,
      [&](int64_t b, int64_t e) {
        for (int64_t y = b; y < e; ++y) rows[size_t(y)] = fn(int(y));
      },
      nullptr, 8);
  return rows;
}
double sumInOrder(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Masks and channels

PixelMask maskFromImage(const Image& img, const std::string& source) {
  int c = img.channelIndex("A");
  if (c < 0 && img.numChannels() == 1) c = 0;
  if (c < 0)
    throw InputError(source, "channels", std::to_string(img.numChannels()) + " without an alpha channel",
                     "a single-channel mask image or an image with an alpha (A) channel");
  PixelMask m;
  m.width = img.width;
  m.height = img.height;
  m.source = source;
  m.on.resize(size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) m.on[size_t(y) * img.width + x] = img.at(x, y, c) > 0.5f ? 1 : 0;
  return m;
}

PixelMask loadMask(const std::string& path) { return maskFromImage(readImage(path), path); }

std::vector<float> colorValues(const Image& img, const std::string& name) {
  std::vector<int> idx;
  const int r = img.channelIndex("R"), g = img.channelIndex("G"), b = img.channelIndex("B");
  if (r >= 0 && g >= 0 && b >= 0) {
    idx = {r, g, b};
  } else {
    for (int c = 0; c < img.numChannels() && idx.size() < 3; ++c)
      if (img.channels[size_t(c)] != "A") idx.push_back(c);
    if (idx.empty())
      throw InputError(name, "channels", std::to_string(img.numChannels()) + " (alpha only)",
                       "colour channels (R, G, B or one grey channel)");
    if (idx.size() < 3) idx = {idx[0], idx[0], idx[0]};  // grey
  }
  const size_t n = size_t(img.width) * img.height, nc = size_t(img.numChannels());
  std::vector<float> out(n * 3);
  for (size_t p = 0; p < n; ++p)
    for (size_t k = 0; k < 3; ++k) out[p * 3 + k] = img.data[p * nc + size_t(idx[k])];
  return out;
}

Image colorImage(const Image& img, const std::string& name) {
  Image out;
  out.width = img.width;
  out.height = img.height;
  out.channels = {"R", "G", "B"};
  out.data = colorValues(img, name);
  return out;
}

void requireSameSize(const Image& a, const Image& b, const std::string& nameA, const std::string& nameB) {
  if (a.width != b.width || a.height != b.height)
    throw InputError(nameA, "size", sizeText(a.width, a.height),
                     "the size of " + nameB + " (" + sizeText(b.width, b.height) + "): images compared must have "
                     "the same size");
}

void requireMaskFits(const PixelMask& mask, int width, int height) {
  if (mask.width != width || mask.height != height)
    throw InputError(mask.source, "size", sizeText(mask.width, mask.height),
                     "the size of the images compared (" + sizeText(width, height) + ")");
  if (mask.count() == 0)
    throw InputError(mask.source, "mask", "no pixel > 0.5", "at least one pixel with a mask value > 0.5");
}

// ---------------------------------------------------------------------------------------
// PSNR

double meanSquaredError(const Image& a, const Image& b, const PixelMask* mask) {
  requireSameSize(a, b, "first image", "second image");
  if (mask) requireMaskFits(*mask, a.width, a.height);
  const std::vector<float> va = colorValues(a, "first image"), vb = colorValues(b, "second image");
  const int w = a.width;
  std::vector<double> rows = perRow(a.height, [&](int y) {
    double s = 0.0;
    for (int x = 0; x < w; ++x) {
      if (mask && !mask->counts(x, y)) continue;
      const size_t p = (size_t(y) * w + x) * 3;
      for (size_t k = 0; k < 3; ++k) {
        const double d = double(va[p + k]) - double(vb[p + k]);
        s += d * d;
      }
    }
    return s;
  });
  const double n = 3.0 * double(mask ? mask->count() : int64_t(a.width) * a.height);
  return n > 0.0 ? sumInOrder(rows) / n : 0.0;
}

double psnrFromMse(double mse, double peak) {
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

double psnr(const Image& a, const Image& b, double peak, const PixelMask* mask) {
  if (!(peak > 0.0) || !std::isfinite(peak))
    throw InputError("", "peak", std::to_string(peak), "a positive, finite PSNR peak value");
  return psnrFromMse(meanSquaredError(a, b, mask), peak);
}

// ---------------------------------------------------------------------------------------
// SSIM

std::vector<double> ssimGaussian(int windowSize, double sigma) {
  std::vector<double> g(size_t(std::max(windowSize, 1)));
  const int r = windowSize / 2;
  double s = 0.0;
  for (int i = 0; i < windowSize; ++i) {
    const double d = i - r;
    g[size_t(i)] = std::exp(-d * d / (2.0 * sigma * sigma));
    s += g[size_t(i)];
  }
  for (double& v : g) v /= s;
  return g;
}

SsimSum ssimPlane(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                  const SsimOptions& opt, const PixelMask* mask) {
  if (opt.windowSize < 1 || opt.windowSize % 2 == 0)
    throw InputError("", "ssim window", std::to_string(opt.windowSize), "an odd window size");
  if (!(opt.sigma > 0.0) || !(opt.dynamicRange > 0.0) || !std::isfinite(opt.dynamicRange))
    throw InputError("", "ssim", "sigma " + std::to_string(opt.sigma) + ", L " + std::to_string(opt.dynamicRange),
                     "positive, finite sigma and dynamic range");
  if (x.size() != size_t(width) * height || y.size() != x.size() ||
      (mask && (mask->width != width || mask->height != height)))
    throw std::invalid_argument("ssimPlane: planes and mask must hold width x height values");
  const int n = opt.windowSize, r = n / 2;
  if (width < n || height < n) return {};
  const std::vector<double> g = ssimGaussian(n, opt.sigma);
  const double C1 = (opt.k1 * opt.dynamicRange) * (opt.k1 * opt.dynamicRange);
  const double C2 = (opt.k2 * opt.dynamicRange) * (opt.k2 * opt.dynamicRange);
  const int outW = width - 2 * r;  // map columns [r, width - r)
  const int outRows = height - 2 * r;

  // Per output row: the six moments, each a separable Gaussian filter of a product plane
  // (m, m x, m y, m x², m y², m x y with m the 0/1 mask), first along x over the window's
  // input rows, then along y.
  constexpr int kMoments = 6;
  std::vector<double> rowSums(size_t(outRows), 0.0);
  std::vector<int64_t> rowCounts(size_t(outRows), 0);
  const int band = 16;
  const int bands = (outRows + band - 1) / band;
  parallelForRange(
      bands,
      [&](int64_t b0, int64_t b1) {
        std::vector<double> h;  // horizontally filtered moments: [input row][moment][outW]
        for (int64_t bi = b0; bi < b1; ++bi) {
          const int oy0 = int(bi) * band, oy1 = std::min(outRows, oy0 + band);
          const int iy0 = oy0, iy1 = oy1 + 2 * r;  // input rows needed
          const int nRows = iy1 - iy0;
          h.assign(size_t(nRows) * kMoments * outW, 0.0);
          for (int iy = iy0; iy < iy1; ++iy) {
            double* hr = &h[size_t(iy - iy0) * kMoments * outW];
            const size_t base = size_t(iy) * width;
            for (int ox = 0; ox < outW; ++ox) {
              double s[kMoments] = {0, 0, 0, 0, 0, 0};
              for (int k = 0; k < n; ++k) {
                const size_t p = base + size_t(ox + k);
                const double m = mask ? (mask->on[p] ? 1.0 : 0.0) : 1.0;
                if (m == 0.0) continue;
                const double xv = x[p], yv = y[p], wk = g[size_t(k)];
                s[0] += wk;
                s[1] += wk * xv;
                s[2] += wk * yv;
                s[3] += wk * (xv * xv);
                s[4] += wk * (yv * yv);
                s[5] += wk * (xv * yv);
              }
              for (int mo = 0; mo < kMoments; ++mo) hr[size_t(mo) * outW + ox] = s[mo];
            }
          }
          for (int oy = oy0; oy < oy1; ++oy) {
            double sum = 0.0;
            int64_t count = 0;
            const int cy = oy + r;  // window centre row in the image
            for (int ox = 0; ox < outW; ++ox) {
              const int cx = ox + r;
              if (mask && !mask->counts(cx, cy)) continue;
              double s[kMoments] = {0, 0, 0, 0, 0, 0};
              for (int k = 0; k < n; ++k) {
                const double* hr = &h[size_t(oy - iy0 + k) * kMoments * outW];
                for (int mo = 0; mo < kMoments; ++mo) s[mo] += g[size_t(k)] * hr[size_t(mo) * outW + ox];
              }
              const double wsum = s[0];
              const double mx = s[1] / wsum, my = s[2] / wsum;
              const double vx = s[3] / wsum - mx * mx, vy = s[4] / wsum - my * my;
              const double cxy = s[5] / wsum - mx * my;
              // Written so that swapping x and y gives the same bits (SSIM is symmetric),
              // and x == y gives exactly 1.
              const double num = (2.0 * (mx * my) + C1) * (2.0 * cxy + C2);
              const double den = ((mx * mx + my * my) + C1) * ((vx + vy) + C2);
              sum += num / den;
              ++count;
            }
            rowSums[size_t(oy)] = sum;
            rowCounts[size_t(oy)] = count;
          }
        }
      },
      nullptr, 1);
  SsimSum out;
  for (int i = 0; i < outRows; ++i) {
    out.sum += rowSums[size_t(i)];
    out.windows += rowCounts[size_t(i)];
  }
  return out;
}

SsimResult ssim(const Image& a, const Image& b, const SsimOptions& opt, const PixelMask* mask) {
  requireSameSize(a, b, "first image", "second image");
  if (mask) requireMaskFits(*mask, a.width, a.height);
  const std::vector<float> va = colorValues(a, "first image"), vb = colorValues(b, "second image");
  const size_t n = size_t(a.width) * a.height;
  auto plane = [&](const std::vector<float>& v, int channel) {
    std::vector<double> p(n);
    for (size_t i = 0; i < n; ++i) {
      const float* c = &v[i * 3];
      p[i] = channel >= 0 ? double(c[channel]) : 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    }
    return p;
  };
  SsimResult res;
  if (opt.channels == SsimChannels::Luminance) {
    SsimSum s = ssimPlane(plane(va, -1), plane(vb, -1), a.width, a.height, opt, mask);
    res.windows = s.windows;
    res.value = s.windows > 0 ? s.sum / double(s.windows) : kNaN;
  } else {
    double total = 0.0;
    for (int c = 0; c < 3; ++c) {
      SsimSum s = ssimPlane(plane(va, c), plane(vb, c), a.width, a.height, opt, mask);
      res.windows = s.windows;
      total += s.windows > 0 ? s.sum / double(s.windows) : kNaN;
    }
    res.value = total / 3.0;
  }
  return res;
}

// ---------------------------------------------------------------------------------------
// CIEDE2000

std::vector<float> deltaE2000Map(const Image& a, const Image& b, const std::string& spaceA,
                                 const std::string& spaceB, double whiteLuminance, const PixelMask* only) {
  requireSameSize(a, b, "first image", "second image");
  if (only) requireMaskFits(*only, a.width, a.height);
  if (!(whiteLuminance > 0.0) || !std::isfinite(whiteLuminance))
    throw InputError("", "white luminance", std::to_string(whiteLuminance), "a positive, finite value");
  const ColorSystem& cs = ColorSystem::instance();
  Image xa = colorImage(a, "first image"), xb = colorImage(b, "second image");
  cs.convertImage(xa, spaceA, "cie_xyz_d65");
  cs.convertImage(xb, spaceB, "cie_xyz_d65");
  // The white of CIELAB: the config's D65 white (lin_rec709 (1,1,1)), so that neutral
  // colours have a* = b* = 0, scaled to the images' white luminance.
  const Vec3 w = cs.convert(Vec3(1.0f), "lin_rec709", "cie_xyz_d65");
  const Vec3d white = Vec3d(double(w.x), double(w.y), double(w.z)) / double(w.y) * whiteLuminance;
  const int width = a.width;
  std::vector<float> map(size_t(a.width) * a.height, 0.0f);
  parallelForRange(
      a.height,
      [&](int64_t y0, int64_t y1) {
        for (int64_t y = y0; y < y1; ++y)
          for (int x = 0; x < width; ++x) {
            const size_t p = size_t(y) * width + x;
            if (only && !only->on[p]) continue;
            const Vec3d A(xa.data[p * 3], xa.data[p * 3 + 1], xa.data[p * 3 + 2]);
            const Vec3d B(xb.data[p * 3], xb.data[p * 3 + 1], xb.data[p * 3 + 2]);
            const double d = ciede2000(xyzToLab(A, white), xyzToLab(B, white));
            map[p] = float(d);
          }
      },
      nullptr, 4);
  return map;
}

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return kNaN;
  p = std::clamp(p, 0.0, 100.0);
  const double rank = p / 100.0 * double(v.size() - 1);
  const size_t k = size_t(std::floor(rank));
  const double frac = rank - double(k);
  std::nth_element(v.begin(), v.begin() + ptrdiff_t(k), v.end());
  const double lo = v[k];
  if (frac == 0.0 || k + 1 >= v.size()) return lo;
  const double hi = *std::min_element(v.begin() + ptrdiff_t(k) + 1, v.end());
  return lo + frac * (hi - lo);
}

DeltaEStats deltaEStats(const std::vector<float>& map, int width, int height, const PixelMask* mask) {
  if (map.size() != size_t(std::max(width, 0)) * size_t(std::max(height, 0)))
    throw std::invalid_argument("deltaEStats: the map must hold width x height values");
  if (mask) requireMaskFits(*mask, width, height);
  std::vector<double> rows = perRow(height, [&](int y) {
    double s = 0.0;
    for (int x = 0; x < width; ++x)
      if (!mask || mask->counts(x, y)) s += double(map[size_t(y) * width + x]);
    return s;
  });
  std::vector<double> values;
  values.reserve(mask ? size_t(mask->count()) : map.size());
  for (size_t i = 0; i < map.size(); ++i)
    if (!mask || mask->on[i]) values.push_back(double(map[i]));
  DeltaEStats st;
  st.pixels = int64_t(values.size());
  if (values.empty()) {
    st.mean = st.p95 = st.max = kNaN;
    return st;
  }
  st.mean = sumInOrder(rows) / double(values.size());
  st.max = *std::max_element(values.begin(), values.end());
  st.p95 = percentile(values, 95.0);
  return st;
}

DeltaEStats deltaE2000(const Image& a, const Image& b, const std::string& space, const PixelMask* mask,
                       double whiteLuminance) {
  requireSameSize(a, b, "first image", "second image");
  if (mask) requireMaskFits(*mask, a.width, a.height);
  return deltaEStats(deltaE2000Map(a, b, space, space, whiteLuminance), a.width, a.height, mask);
}

// ---------------------------------------------------------------------------------------
// All metrics

const char* metricValuesName(MetricValues v) { return v == MetricValues::Encoded ? "encoded" : "linear"; }
const char* ssimChannelsName(SsimChannels c) { return c == SsimChannels::Luminance ? "luminance" : "channels"; }

ImageMetrics compareImages(const Image& a, const Image& b, const CompareOptions& opt, const PixelMask* mask,
                           const std::string& nameA, const std::string& nameB, std::vector<float>* deltaEMap) {
  requireSameSize(a, b, nameA, nameB);
  if (mask) requireMaskFits(*mask, a.width, a.height);
  if (!(opt.peak > 0.0) || !std::isfinite(opt.peak))
    throw InputError("", "peak", std::to_string(opt.peak), "a positive, finite peak value");
  const ColorSystem& cs = ColorSystem::instance();
  const std::string target = opt.values == MetricValues::Encoded ? "srgb" : "lin_rec709";
  Image ca = colorImage(a, nameA), cb = colorImage(b, nameB);
  cs.convertImage(ca, opt.spaceA, target);
  cs.convertImage(cb, opt.spaceB, target);

  ImageMetrics m;
  m.width = a.width;
  m.height = a.height;
  m.pixels = mask ? mask->count() : int64_t(a.width) * a.height;
  m.psnrDb = psnr(ca, cb, opt.peak, mask);
  SsimOptions so;
  so.dynamicRange = opt.peak;
  so.channels = opt.ssimChannels;
  const SsimResult s = ssim(ca, cb, so, mask);
  m.ssim = s.value;
  m.ssimWindows = s.windows;
  // The whole map when the caller keeps it (an error map), else only what the statistics read.
  std::vector<float> de =
      deltaE2000Map(a, b, opt.spaceA, opt.spaceB, opt.whiteLuminance, deltaEMap ? nullptr : mask);
  m.deltaE = deltaEStats(de, a.width, a.height, mask);
  if (deltaEMap) *deltaEMap = std::move(de);
  {
    const Image ra = colorImage(a, nameA), rb = colorImage(b, nameB);
    double se = 0.0, sum = 0.0;
    int64_t n = 0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x) {
        if (mask && !mask->on[size_t(y) * mask->width + x]) continue;
        for (int c = 0; c < 3; ++c) {
          const double d = double(rb.at(x, y, c)) - ra.at(x, y, c);
          se += d * d;
          sum += ra.at(x, y, c);
        }
        n += 3;
      }
    m.rmseRelative = n > 0 && sum != 0.0 ? std::sqrt(se / double(n)) / (sum / double(n)) : NAN;
  }
  return m;
}

ImageMetrics compareImageFiles(const std::string& pathA, const std::string& pathB, const CompareOptions& opt,
                               const std::string& maskPath) {
  const Image a = readImage(pathA), b = readImage(pathB);
  requireSameSize(a, b, pathA, pathB);
  if (maskPath.empty()) return compareImages(a, b, opt, nullptr, pathA, pathB);
  const PixelMask mask = loadMask(maskPath);
  return compareImages(a, b, opt, &mask, pathA, pathB);
}

std::string defaultColorSpaceForFile(const std::string& path) {
  const std::optional<FileKind> k = fileKindOf(path);
  return k == FileKind::Exr || k == FileKind::Hdr || k == FileKind::Pfm ? "lin_rec709" : "srgb";
}

Json metricsJson(const ImageMetrics& m) {
  auto num = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json j;
  j["psnr_db"] = num(m.psnrDb);
  j["ssim"] = num(m.ssim);
  j["de2000_mean"] = num(m.deltaE.mean);
  j["de2000_p95"] = num(m.deltaE.p95);
  j["de2000_max"] = num(m.deltaE.max);
  j["rmse_relative"] = num(m.rmseRelative);
  j["pixels"] = m.pixels;
  j["ssim_windows"] = m.ssimWindows;
  j["width"] = m.width;
  j["height"] = m.height;
  return j;
}

std::string formatPsnr(double psnrDb) {
  if (std::isinf(psnrDb)) return psnrDb > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", psnrDb);
  return buf;
}

std::vector<std::string> metricsCsvHeader(const std::string& labelColumn) {
  return {labelColumn, "psnr_db", "ssim", "de2000_mean", "de2000_p95", "de2000_max", "pixels"};
}

std::vector<std::string> metricsCsvRow(const std::string& label, const ImageMetrics& m) {
  auto num = [](double v) {
    if (std::isnan(v)) return std::string("nan");
    if (std::isinf(v)) return std::string(v > 0 ? "inf" : "-inf");
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return std::string(buf);
  };
  return {label, num(m.psnrDb), num(m.ssim), num(m.deltaE.mean), num(m.deltaE.p95), num(m.deltaE.max),
          std::to_string(m.pixels)};
}

std::string metricsText(const ImageMetrics& m, const CompareOptions& opt) {
  std::ostringstream o;
  char buf[256];
  const char* values = opt.values == MetricValues::Encoded ? "sRGB-encoded values" : "linear Rec.709 values";
  std::snprintf(buf, sizeof buf, "pixels       %lld of %d x %d\n", static_cast<long long>(m.pixels), m.width,
                m.height);
  o << buf;
  if (std::isfinite(m.rmseRelative))
    std::snprintf(buf, sizeof buf, "RMSE         %.4g%% of A's mean  (B - A, linear input values, R, G, B)\n",
                  100.0 * m.rmseRelative);
  else  // A is black: a share of its mean means nothing
    std::snprintf(buf, sizeof buf, "RMSE         n/a  (A's mean is 0: no relative RMSE)\n");
  o << buf;
  o << "PSNR         " << formatPsnr(m.psnrDb) << " dB  (" << values << ", peak " << opt.peak
    << (std::isinf(m.psnrDb) ? "; identical" : "") << ")\n";
  if (m.ssimWindows > 0)
    std::snprintf(buf, sizeof buf, "SSIM         %.6f  (%s, L = %g, 11x11 Gaussian, sigma 1.5, %lld windows)\n",
                  m.ssim, opt.ssimChannels == SsimChannels::Luminance ? "luminance" : "mean of R, G, B", opt.peak,
                  static_cast<long long>(m.ssimWindows));
  else
    std::snprintf(buf, sizeof buf, "SSIM         n/a  (no 11x11 window inside the image and the mask)\n");
  o << buf;
  std::snprintf(buf, sizeof buf, "dE2000 mean  %.4f\ndE2000 p95   %.4f\ndE2000 max   %.4f\n", m.deltaE.mean,
                m.deltaE.p95, m.deltaE.max);
  o << buf;
  o << "spaces       A: " << opt.spaceA << ", B: " << opt.spaceB << "\n";
  return o.str();
}

}  // namespace inim
