// Image metrics against analytic values and an independent naive implementation:
// PSNR of a known uniform error, SSIM identities, the flat-image luminance term and a
// per-window reference, CIEDE2000 of a uniform shift, percentiles, and masks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "analysis/metrics.h"
#include "core/error.h"
#include "core/parallel.h"
#include "fixtures.h"
#include "spectral/color.h"

using namespace inim;
using fixtures::expectInputError;
using fixtures::scratchPath;

namespace {

// A smooth pattern plus seeded noise, in [0, 1].
Image testImage(int w, int h, uint32_t seed, int channels = 3) {
  std::vector<std::string> names = channels == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
  if (channels == 4) names.push_back("A");
  Image img(w, h, names);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 0.2f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < std::min(channels, 3); ++c)
        img.at(x, y, c) = 0.4f + 0.3f * std::sin(0.37f * x + 0.21f * y + c) + u(rng);
  if (channels == 4)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) img.at(x, y, 3) = 1.0f;
  return img;
}

Image flat(int w, int h, Vec3 c) {
  Image img(w, h, {"R", "G", "B"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
  return img;
}

Image addNoise(const Image& a, float sigma, uint32_t seed) {
  Image b = a;
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, sigma);
  for (float& v : b.data) v += n(rng);
  return b;
}

// Naive SSIM: every valid window evaluated directly with 2-D Gaussian weights
// exp(-(dx²+dy²)/(2σ²)) normalised over the window, optionally times a 0/1 mask.
double naiveSsimPlane(const std::vector<double>& x, const std::vector<double>& y, int w, int h, double L,
                      const PixelMask* mask = nullptr) {
  const double C1 = (0.01 * L) * (0.01 * L), C2 = (0.03 * L) * (0.03 * L), sigma = 1.5;
  double total = 0.0;
  int count = 0;
  for (int cy = 5; cy < h - 5; ++cy)
    for (int cx = 5; cx < w - 5; ++cx) {
      if (mask && !mask->counts(cx, cy)) continue;
      double W = 0, sx = 0, sy = 0;
      for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
          if (mask && !mask->counts(cx + dx, cy + dy)) continue;
          const double wt = std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
          const size_t p = size_t(cy + dy) * w + (cx + dx);
          W += wt, sx += wt * x[p], sy += wt * y[p];
        }
      const double mx = sx / W, my = sy / W;
      double vx = 0, vy = 0, cxy = 0;
      for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
          if (mask && !mask->counts(cx + dx, cy + dy)) continue;
          const double wt = std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma)) / W;
          const size_t p = size_t(cy + dy) * w + (cx + dx);
          vx += wt * (x[p] - mx) * (x[p] - mx);
          vy += wt * (y[p] - my) * (y[p] - my);
          cxy += wt * (x[p] - mx) * (y[p] - my);
        }
      total += (2 * mx * my + C1) * (2 * cxy + C2) / ((mx * mx + my * my + C1) * (vx + vy + C2));
      ++count;
    }
  return total / count;
}

std::vector<double> lumaPlane(const Image& img) {
  std::vector<double> p(size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      p[size_t(y) * img.width + x] = 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
  return p;
}
std::vector<double> channelPlane(const Image& img, int c) {
  std::vector<double> p(size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) p[size_t(y) * img.width + x] = img.at(x, y, c);
  return p;
}

// Keeps pixels whose (x + 2y) % 5 != 0, plus a hole in the middle excluded.
PixelMask patternMask(int w, int h) {
  Image m(w, h, {"Y"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool hole = std::abs(x - w / 2) < 4 && std::abs(y - h / 2) < 3;
      m.at(x, y, 0) = ((x + 2 * y) % 5 != 0 && !hole) ? 0.9f : 0.2f;
    }
  return maskFromImage(m, "pattern mask");
}

Vec3d labOf(const Vec3& rgb, const std::string& space) {
  const ColorSystem& cs = ColorSystem::instance();
  const Vec3 xyz = cs.convert(rgb, space, "cie_xyz_d65");
  const Vec3 w = cs.convert(Vec3(1.0f), "lin_rec709", "cie_xyz_d65");
  const Vec3d white = Vec3d(w) / double(w.y);
  return xyzToLab(Vec3d(xyz), white);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// PSNR

TEST(Psnr, IdenticalImagesAreInfinite) {
  Image a = testImage(24, 20, 1);
  const double p = psnr(a, a);
  EXPECT_TRUE(std::isinf(p) && p > 0.0);
  EXPECT_EQ(meanSquaredError(a, a), 0.0);
  EXPECT_EQ(formatPsnr(p), "inf");
  EXPECT_TRUE(metricsJson(ImageMetrics{p, 1.0, 1, {}, 1, 1, 1})["psnr_db"].is_null());
}

TEST(Psnr, UniformAdditiveErrorMatchesFormula) {
  // Values and error exactly representable, so the error is exactly e in float.
  Image a(37, 23, {"R", "G", "B"});
  for (size_t i = 0; i < a.data.size(); ++i) a.data[i] = float(int(i * 7919 % 769)) / 1024.0f;  // k / 2^10 <= 0.75
  const float e = 1.0f / 64.0f;
  Image b = a;
  for (float& v : b.data) v += e;
  for (double peak : {1.0, 2.0, 255.0 / 256.0}) {
    const double expected = 10.0 * std::log10(peak * peak / (double(e) * e));
    EXPECT_NEAR(psnr(a, b, peak), expected, 1e-9) << "peak " << peak;
    EXPECT_NEAR(psnr(b, a, peak), expected, 1e-9);
  }
  EXPECT_DOUBLE_EQ(meanSquaredError(a, b), double(e) * e);
  // Subtracting the error instead gives the same PSNR.
  Image c = a;
  for (float& v : c.data) v -= e;
  EXPECT_NEAR(psnr(a, c, 1.0), 10.0 * std::log10(1.0 / (double(e) * e)), 1e-9);
}

TEST(Psnr, GreyImageEqualsRgbGrey) {
  Image g = testImage(16, 16, 3, 1);
  Image rgb(16, 16, {"R", "G", "B", "A"});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = g.at(x, y, 0);
      rgb.at(x, y, 3) = 0.25f * x;  // alpha is ignored
    }
  EXPECT_TRUE(std::isinf(psnr(g, rgb)));
  EXPECT_EQ(ssim(g, rgb).value, 1.0);
}

// ---------------------------------------------------------------------------------------
// SSIM

TEST(Ssim, SelfIsExactlyOneAndSymmetric) {
  Image a = testImage(48, 40, 11), b = addNoise(a, 0.05f, 12);
  for (SsimChannels ch : {SsimChannels::Luminance, SsimChannels::PerChannelMean}) {
    SsimOptions o;
    o.channels = ch;
    SsimResult self = ssim(a, a, o);
    EXPECT_EQ(self.value, 1.0);
    EXPECT_EQ(self.windows, int64_t(48 - 10) * (40 - 10));
    EXPECT_EQ(ssim(a, b, o).value, ssim(b, a, o).value);
    EXPECT_LT(ssim(a, b, o).value, 1.0);
  }
}

TEST(Ssim, FlatImagesGiveTheLuminanceTerm) {
  for (auto [vx, vy, L] : {std::tuple{0.3f, 0.5f, 1.0}, std::tuple{0.1f, 0.9f, 1.0}, std::tuple{20.0f, 35.0f, 255.0}}) {
    Image a = flat(20, 17, Vec3(vx)), b = flat(20, 17, Vec3(vy));
    SsimOptions o;
    o.dynamicRange = L;
    const double C1 = (0.01 * L) * (0.01 * L);
    const double mx = vx, my = vy;
    const double l = (2 * mx * my + C1) / (mx * mx + my * my + C1);
    EXPECT_NEAR(ssim(a, b, o).value, l, 1e-9 * std::max(1.0, l)) << vx << " vs " << vy;
    o.channels = SsimChannels::PerChannelMean;
    EXPECT_NEAR(ssim(a, b, o).value, l, 1e-9);
  }
}

TEST(Ssim, DecreasesWithNoise) {
  Image a = testImage(64, 48, 21);
  double prev = 1.0;
  for (float sigma : {0.005f, 0.02f, 0.05f, 0.1f, 0.2f}) {
    const double s = ssim(a, addNoise(a, sigma, 22)).value;
    EXPECT_LT(s, prev) << "sigma " << sigma;
    prev = s;
  }
  EXPECT_LT(prev, 0.8);
}

TEST(Ssim, MatchesNaivePerWindowReference) {
  Image a = testImage(41, 33, 31), b = addNoise(a, 0.07f, 32);
  for (int c = 0; c < 3; ++c)  // a channel-dependent gain too
    for (int y = 0; y < b.height; ++y)
      for (int x = 0; x < b.width; ++x) b.at(x, y, c) *= 0.9f + 0.05f * c;
  const double lum = naiveSsimPlane(lumaPlane(a), lumaPlane(b), a.width, a.height, 1.0);
  EXPECT_NEAR(ssim(a, b).value, lum, 1e-6);
  SsimOptions o;
  o.channels = SsimChannels::PerChannelMean;
  double per = 0.0;
  for (int c = 0; c < 3; ++c) per += naiveSsimPlane(channelPlane(a, c), channelPlane(b, c), a.width, a.height, 1.0) / 3.0;
  EXPECT_NEAR(ssim(a, b, o).value, per, 1e-6);
  // A different dynamic range.
  o = {};
  o.dynamicRange = 2.5;
  EXPECT_NEAR(ssim(a, b, o).value, naiveSsimPlane(lumaPlane(a), lumaPlane(b), a.width, a.height, 2.5), 1e-6);
  // With a mask: Gaussian x mask weights.
  PixelMask m = patternMask(a.width, a.height);
  EXPECT_NEAR(ssim(a, b, {}, &m).value, naiveSsimPlane(lumaPlane(a), lumaPlane(b), a.width, a.height, 1.0, &m), 1e-6);
}

TEST(Ssim, TooSmallForTheWindowHasNoWindows) {
  Image a = testImage(10, 30, 1);
  SsimResult r = ssim(a, a);
  EXPECT_EQ(r.windows, 0);
  EXPECT_TRUE(std::isnan(r.value));
  ImageMetrics m = compareImages(a, addNoise(a, 0.01f, 2));
  EXPECT_EQ(m.ssimWindows, 0);
  EXPECT_TRUE(metricsJson(m)["ssim"].is_null());
}

TEST(Ssim, GaussianWindowIsNormalised) {
  const std::vector<double> g = ssimGaussian(11, 1.5);
  double s = 0;
  for (double v : g) s += v;
  EXPECT_NEAR(s, 1.0, 1e-15);
  EXPECT_NEAR(g[5] / g[4], std::exp(1.0 / (2 * 2.25)), 1e-12);
}

// ---------------------------------------------------------------------------------------
// CIEDE2000

TEST(DeltaE2000, IdenticalImagesAreZero) {
  Image a = testImage(20, 12, 41);
  DeltaEStats s = deltaE2000(a, a);
  EXPECT_EQ(s.mean, 0.0);
  EXPECT_EQ(s.p95, 0.0);
  EXPECT_EQ(s.max, 0.0);
  EXPECT_EQ(s.pixels, 240);
}

TEST(DeltaE2000, UniformShiftMatchesTheColourPair) {
  struct Case {
    Vec3 c1, c2;
    std::string space;
  };
  for (const Case& k : {Case{{0.2f, 0.3f, 0.4f}, {0.25f, 0.28f, 0.35f}, "lin_rec709"},
                        Case{{0.8f, 0.1f, 0.1f}, {0.7f, 0.15f, 0.1f}, "lin_rec709"},
                        Case{{0.5f, 0.5f, 0.5f}, {0.6f, 0.5f, 0.4f}, "srgb"},
                        Case{{0.3f, 0.6f, 0.2f}, {0.3f, 0.55f, 0.25f}, "acescg"},
                        Case{{0.4f, 0.42f, 0.3f}, {0.45f, 0.4f, 0.33f}, "cie_xyz_d65"}}) {
    const double expected = ciede2000(labOf(k.c1, k.space), labOf(k.c2, k.space));
    ASSERT_GT(expected, 0.5);
    DeltaEStats s = deltaE2000(flat(13, 9, k.c1), flat(13, 9, k.c2), k.space);
    EXPECT_NEAR(s.mean, expected, 1e-5 * expected) << k.space;
    EXPECT_NEAR(s.p95, expected, 1e-5 * expected) << k.space;
    EXPECT_NEAR(s.max, expected, 1e-5 * expected) << k.space;
  }
}

TEST(DeltaE2000, NeutralWhiteIsAchromatic) {
  // The CIELAB white is the config's D65 white: lin_rec709 (1,1,1) -> L* = 100, a* = b* = 0.
  const Vec3d lab = labOf(Vec3(1.0f), "lin_rec709");
  EXPECT_NEAR(lab.x, 100.0, 1e-4);
  EXPECT_NEAR(lab.y, 0.0, 1e-4);
  EXPECT_NEAR(lab.z, 0.0, 1e-4);
}

TEST(Percentile, KnownDistributions) {
  std::vector<double> v;
  for (int i = 0; i <= 100; ++i) v.push_back(100 - i);
  EXPECT_DOUBLE_EQ(percentile(v, 95.0), 95.0);
  std::vector<double> w;
  for (int i = 0; i < 100; ++i) w.push_back(double((i * 37) % 100));  // a permutation of 0..99
  EXPECT_NEAR(percentile(w, 95.0), 94.05, 1e-12);                    // rank 0.95 * 99 = 94.05
  std::vector<double> one{3.5};
  EXPECT_EQ(percentile(one, 95.0), 3.5);
  std::vector<double> none;
  EXPECT_TRUE(std::isnan(percentile(none, 95.0)));
  EXPECT_DOUBLE_EQ(percentile(w, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(percentile(w, 100.0), 99.0);
}

TEST(DeltaE2000, StatsOfAKnownMap) {
  // 10 x 10 map holding 0..99: mean 49.5, p95 94.05, max 99.
  std::vector<float> map(100);
  for (int i = 0; i < 100; ++i) map[size_t(i)] = float((i * 37) % 100);
  DeltaEStats s = deltaEStats(map, 10, 10);
  EXPECT_DOUBLE_EQ(s.mean, 49.5);
  EXPECT_NEAR(s.p95, 94.05, 1e-12);
  EXPECT_EQ(s.max, 99.0);
  // 5% of the pixels differ by d, the rest by 0: p95 interpolates between 0 and d.
  Image a = flat(20, 10, Vec3(0.3f)), b = a;
  for (int x = 0; x < 10; ++x) b.at(x, 0, 0) = 0.4f;  // 10 of 200 pixels = 5%
  const double d = ciede2000(labOf(Vec3(0.3f), "lin_rec709"), labOf(Vec3(0.4f, 0.3f, 0.3f), "lin_rec709"));
  DeltaEStats t = deltaE2000(a, b);
  EXPECT_NEAR(t.mean, d * 10 / 200, 1e-5 * d);
  EXPECT_NEAR(t.p95, 0.05 * d, 1e-5 * d);  // rank 0.95 * 199 = 189.05: 0 + 0.05 (d - 0)
  EXPECT_NEAR(t.max, d, 1e-5 * d);
}

// The map compareImages hands out is the one its statistics come from: every pixel's CIEDE2000
// (also those off the mask), as deltaE2000Map gives it.
TEST(DeltaE2000, CompareImagesGivesTheMapOfItsStatistics) {
  const int w = 31, h = 23;
  Image a = testImage(w, h, 71), b = addNoise(a, 0.05f, 72);
  PixelMask m = patternMask(w, h);
  CompareOptions o;
  o.spaceA = o.spaceB = "srgb";
  std::vector<float> map;
  const ImageMetrics r = compareImages(a, b, o, &m, "A", "B", &map);
  EXPECT_EQ(map, deltaE2000Map(a, b, "srgb", "srgb"));
  const DeltaEStats s = deltaEStats(map, w, h, &m);
  EXPECT_EQ(r.deltaE.mean, s.mean);
  EXPECT_EQ(r.deltaE.p95, s.p95);
  EXPECT_EQ(r.deltaE.max, s.max);
}

// A map on a mask only (what compareImages computes when the caller keeps no map) is the full
// map there and 0 elsewhere, and compareImages' statistics are the same either way.
TEST(DeltaE2000, MapOnAMaskIsTheFullMapThere) {
  const int w = 31, h = 23;
  Image a = testImage(w, h, 73), b = addNoise(a, 0.05f, 74);
  PixelMask m = patternMask(w, h);
  const std::vector<float> full = deltaE2000Map(a, b, "srgb", "srgb"), onMask = deltaE2000Map(a, b, "srgb", "srgb", 1.0, &m);
  int offMask = 0;
  for (size_t i = 0; i < full.size(); ++i) {
    EXPECT_EQ(onMask[i], m.on[i] ? full[i] : 0.0f) << i;
    offMask += !m.on[i] && full[i] > 0.0f;
  }
  EXPECT_GT(offMask, 0);  // the mask does leave out pixels that differ
  CompareOptions o;
  o.spaceA = o.spaceB = "srgb";
  std::vector<float> kept;
  const ImageMetrics withMap = compareImages(a, b, o, &m, "A", "B", &kept), without = compareImages(a, b, o, &m);
  EXPECT_EQ(withMap.deltaE.mean, without.deltaE.mean);
  EXPECT_EQ(withMap.deltaE.p95, without.deltaE.p95);
  EXPECT_EQ(withMap.deltaE.max, without.deltaE.max);
  EXPECT_THROW(deltaE2000Map(a, b, "srgb", "srgb", 1.0, &(m = patternMask(w + 1, h))), std::exception);
}

// ---------------------------------------------------------------------------------------
// Masks

TEST(Mask, ExcludedPixelsDoNotChangeAnyMetric) {
  const int w = 45, h = 38;
  Image a = testImage(w, h, 51), b = addNoise(a, 0.04f, 52);
  PixelMask m = patternMask(w, h);
  Image b2 = b, a2 = a;
  std::mt19937 rng(53);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (!m.counts(x, y))
        for (int c = 0; c < 3; ++c) b2.at(x, y, c) = 3.0f * u(rng), a2.at(x, y, c) = u(rng);
  for (MetricValues v : {MetricValues::Encoded, MetricValues::Linear}) {
    CompareOptions o;
    o.values = v;
    const ImageMetrics r1 = compareImages(a, b, o, &m), r2 = compareImages(a2, b2, o, &m);
    EXPECT_EQ(r1.psnrDb, r2.psnrDb);
    EXPECT_EQ(r1.ssim, r2.ssim);
    EXPECT_EQ(r1.deltaE.mean, r2.deltaE.mean);
    EXPECT_EQ(r1.deltaE.p95, r2.deltaE.p95);
    EXPECT_EQ(r1.deltaE.max, r2.deltaE.max);
    EXPECT_EQ(r1.pixels, m.count());
    EXPECT_EQ(r1.pixels, r2.pixels);
    // ... while without the mask they do.
    EXPECT_NE(compareImages(a, b, o).psnrDb, compareImages(a2, b2, o).psnrDb);
  }
  SsimOptions so;
  so.channels = SsimChannels::PerChannelMean;
  EXPECT_EQ(ssim(a, b, so, &m).value, ssim(a2, b2, so, &m).value);
  EXPECT_EQ(psnr(a, b, 1.0, &m), psnr(a2, b2, 1.0, &m));
}

TEST(Mask, FullMaskEqualsNoMask) {
  Image a = testImage(30, 25, 61), b = addNoise(a, 0.03f, 62);
  Image all(30, 25, {"Y"});
  std::fill(all.data.begin(), all.data.end(), 1.0f);
  PixelMask m = maskFromImage(all);
  const ImageMetrics r1 = compareImages(a, b), r2 = compareImages(a, b, {}, &m);
  EXPECT_EQ(r1.psnrDb, r2.psnrDb);
  EXPECT_NEAR(r1.ssim, r2.ssim, 1e-14);
  EXPECT_EQ(r1.deltaE.mean, r2.deltaE.mean);
  EXPECT_EQ(r1.deltaE.p95, r2.deltaE.p95);
}

TEST(Mask, FromAlphaOrSingleChannel) {
  Image rgba = testImage(8, 6, 71, 4);
  for (int x = 0; x < 8; ++x) rgba.at(x, 2, 3) = 0.5f;  // not > 0.5
  PixelMask m = maskFromImage(rgba, "rgba.png");
  EXPECT_EQ(m.count(), 40);
  EXPECT_FALSE(m.counts(3, 2));
  EXPECT_TRUE(m.counts(3, 3));
  Image rgb = testImage(8, 6, 71);
  // An RGB image without alpha is not a mask.
  EXPECT_NE(std::string(expectInputError([&] { maskFromImage(rgb, "rgb.png"); }).what()).find("rgb.png"),
            std::string::npos);
  Image zero(8, 6, {"Y"});
  PixelMask none = maskFromImage(zero, "zero.png");
  EXPECT_THROW(compareImages(rgb, rgb, {}, &none), InputError);
  Image small(4, 6, {"Y"});
  PixelMask wrong = maskFromImage(small, "small.png");
  EXPECT_NE(std::string(expectInputError([&] { compareImages(rgb, rgb, {}, &wrong); }).what()).find("small.png"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------
// Bad input, files, determinism

TEST(Compare, SizeMismatchNamesBothImages) {
  const std::string msg = expectInputError([] {
                            compareImages(testImage(10, 10, 1), testImage(12, 10, 1), {}, nullptr, "ref.exr", "rec.exr");
                          }).what();
  EXPECT_NE(msg.find("ref.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("rec.exr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("10 x 10"), std::string::npos) << msg;
  EXPECT_NE(msg.find("12 x 10"), std::string::npos) << msg;
}

TEST(Compare, FilesNaNAndMissing) {
  const std::string aFile = scratchPath("a.exr"), nanFile = scratchPath("nan.exr");
  Image a = testImage(16, 16, 81);
  writeImage(a, aFile);
  Image n = a;
  n.at(3, 4, 1) = std::numeric_limits<float>::quiet_NaN();
  writeImage(n, nanFile);
  ImageMetrics same = compareImageFiles(aFile, aFile);
  EXPECT_TRUE(std::isinf(same.psnrDb));
  EXPECT_EQ(same.ssim, 1.0);
  EXPECT_EQ(same.deltaE.mean, 0.0);
  const std::string nanMessage = expectInputError([&] { compareImageFiles(aFile, nanFile); }).what();
  EXPECT_NE(nanMessage.find("nan.exr"), std::string::npos);
  EXPECT_NE(nanMessage.find("NaN"), std::string::npos);
  expectInputError([&] { compareImageFiles(aFile, scratchPath("missing.exr")); });
  EXPECT_EQ(defaultColorSpaceForFile("x/y.EXR"), "lin_rec709");
  EXPECT_EQ(defaultColorSpaceForFile("x/y.png"), "srgb");
}

TEST(Compare, EncodedValuesOfSrgbImagesAreTheStoredValues) {
  // For images declared srgb, "encoded" metrics use the stored values unchanged.
  Image a = testImage(24, 24, 91), b = addNoise(a, 0.02f, 92);
  CompareOptions o;
  o.spaceA = o.spaceB = "srgb";
  const ImageMetrics m = compareImages(a, b, o);
  EXPECT_EQ(m.psnrDb, psnr(a, b));
  EXPECT_EQ(m.ssim, ssim(a, b).value);
  // Linear values of lin_rec709 images likewise.
  o = {};
  o.values = MetricValues::Linear;
  EXPECT_EQ(compareImages(a, b, o).psnrDb, psnr(a, b));
}

TEST(Compare, DeterministicAcrossThreadCounts) {
  Image a = testImage(150, 90, 101), b = addNoise(a, 0.05f, 102);
  PixelMask m = patternMask(150, 90);
  ImageMetrics r1, r2;
  {
    ThreadLimit one(1);
    r1 = compareImages(a, b, {}, &m);
  }
  r2 = compareImages(a, b, {}, &m);
  EXPECT_EQ(r1.psnrDb, r2.psnrDb);
  EXPECT_EQ(r1.ssim, r2.ssim);
  EXPECT_EQ(r1.deltaE.mean, r2.deltaE.mean);
  EXPECT_EQ(r1.deltaE.p95, r2.deltaE.p95);
}

TEST(Compare, CsvRowsAndText) {
  ImageMetrics m;
  m.psnrDb = std::numeric_limits<double>::infinity();
  m.ssim = 1.0;
  m.deltaE = {0.25, 0.5, 2.0, 12};
  m.pixels = 12;
  EXPECT_EQ(metricsCsvHeader(), (std::vector<std::string>{"view", "psnr_db", "ssim", "de2000_mean", "de2000_p95",
                                                          "de2000_max", "pixels"}));
  EXPECT_EQ(metricsCsvRow("0°", m), (std::vector<std::string>{"0°", "inf", "1", "0.25", "0.5", "2", "12"}));
  m.psnrDb = 31.25;
  m.ssimWindows = 3;
  const std::string text = metricsText(m, {});
  EXPECT_NE(text.find("31.2500 dB"), std::string::npos) << text;
  EXPECT_NE(text.find("dE2000 p95   0.5000"), std::string::npos) << text;
}

TEST(RelativeRmse, MatchesTheFormulaWithAndWithoutAMask) {
  // A = (2, 2, 2) everywhere; B differs by 0.2 in R: RMSE over (pixel, channel) =
  // sqrt(0.04 / 3), relative to A's mean 2. A mask of half the pixels, where B = A, gives 0.
  const Image a = flat(16, 12, Vec3(2.0f));
  Image b = a;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      if (x < 8) b.at(x, y, 0) += 0.2f;
  const ImageMetrics all = compareImages(a, b);
  EXPECT_NEAR(all.rmseRelative, std::sqrt(0.5 * 0.04 / 3.0) / 2.0, 1e-6);
  PixelMask m;
  m.width = a.width;
  m.height = a.height;
  m.on.assign(size_t(a.width) * a.height, 0);
  for (int y = 0; y < a.height; ++y)
    for (int x = 8; x < a.width; ++x) m.on[size_t(y) * a.width + x] = 1;
  EXPECT_NEAR(compareImages(a, b, {}, &m).rmseRelative, 0.0, 1e-12);
  EXPECT_TRUE(std::isnan(compareImages(flat(16, 12, Vec3(0.0f)), b).rmseRelative));
  EXPECT_TRUE(metricsJson(all).contains("rmse_relative"));
}
