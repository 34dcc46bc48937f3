// Error against depth (analysis/depth_error.h): synthetic images whose error is known at every
// depth (rec = ref (1 + k z)) give back k |z| per bin; pixels that are masked out or only
// partly covered have no influence; the default range is the 1st..99th percentile; sparse bins
// keep their count with NaN metrics; and the figure marks the planes it is given.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/depth_error.h"
#include "analysis/metrics.h"
#include "expect_input_error.h"

using namespace inim;

namespace {

// 24 columns per row, one per bin of [-24, 24] (2 mm wide): column x sees z = -23 + 2 x (the
// bin centres), every pixel covered. The reference's colour varies by row, the reconstruction is
// ref (1 + k z).
struct Synthetic {
  Image ref, rec;
  std::vector<float> z, a;
};

Synthetic linearError(int rows, double k) {
  const int W = 24;
  Synthetic s{Image(W, rows, {"R", "G", "B"}), Image(W, rows, {"R", "G", "B"}), {}, {}};
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < W; ++x) {
      const double z = -23.0 + 2.0 * x;
      const float c[3] = {0.1f + 0.02f * float(y % 7), 0.3f, 0.5f - 0.01f * float(y % 5)};
      for (int ch = 0; ch < 3; ++ch) {
        s.ref.at(x, y, ch) = c[ch];
        s.rec.at(x, y, ch) = float(c[ch] * (1.0 + k * z));
      }
      s.z.push_back(float(z));
      s.a.push_back(1.0f);
    }
  return s;
}

DepthBinning fixedBins() {
  DepthBinning b;
  b.minZ = -24.0;
  b.maxZ = 24.0;
  b.count = 24;
  return b;
}

}  // namespace

TEST(DepthError, RelativeRmseIsTheKnownErrorOfEachDepth) {
  const double k = 0.01;
  const Synthetic s = linearError(30, k);
  const std::vector<DepthBin> bins = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins());
  ASSERT_EQ(bins.size(), 24u);
  for (int i = 0; i < 24; ++i) {
    const DepthBin& b = bins[size_t(i)];
    const double zc = -23.0 + 2.0 * i;
    EXPECT_NEAR(b.zLo, zc - 1.0, 1e-12);
    EXPECT_NEAR(b.zHi, zc + 1.0, 1e-12);
    EXPECT_NEAR(b.zCentre, zc, 1e-12);
    EXPECT_EQ(b.pixels, 30);
    // |rec - ref| = k |z| |ref| at every pixel of the bin, so the ratio of the RMS is k |z|.
    EXPECT_NEAR(b.relRmse, k * std::abs(zc), 1e-6) << "z = " << zc;
  }
  // CIEDE2000 (of the two images as linear Rec.709) grows with the error, on both sides of z = 0.
  for (int i = 12; i + 1 < 24; ++i) EXPECT_GT(bins[size_t(i) + 1].de2000Mean, bins[size_t(i)].de2000Mean);
  for (int i = 11; i > 0; --i) EXPECT_GT(bins[size_t(i) - 1].de2000Mean, bins[size_t(i)].de2000Mean);
}

TEST(DepthError, MeanDeltaEIsThePerPixelMapsMeanOverTheBin) {
  const Synthetic s = linearError(24, 0.0);
  std::vector<float> de(s.z.size());
  for (size_t i = 0; i < de.size(); ++i) de[i] = std::abs(s.z[i]) + float((i / 24) % 3);  // row y: |z| + y mod 3
  const std::vector<DepthBin> bins = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins(), &de);
  for (const DepthBin& b : bins) {
    EXPECT_NEAR(b.de2000Mean, std::abs(b.zCentre) + 1.0, 1e-4) << b.zCentre;  // 24 rows: 8 each of 0, 1, 2
    EXPECT_EQ(b.relRmse, 0.0);
  }
}

TEST(DepthError, MaskedOutAndPartlyCoveredPixelsDoNotCount) {
  const Synthetic clean = linearError(30, 0.01);
  Synthetic s = clean;
  PixelMask mask{s.ref.width, s.ref.height, std::vector<uint8_t>(s.z.size(), 1), "test mask"};
  // Rows 0-4 masked out, rows 5-9 half covered: their reconstruction is wildly wrong.
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < s.ref.width; ++x) {
      for (int c = 0; c < 3; ++c) s.rec.at(x, y, c) = 5.0f;
      const size_t i = size_t(y) * size_t(s.ref.width) + size_t(x);
      if (y < 5) mask.on[i] = 0;
      else s.a[i] = 0.49f;
    }
  const std::vector<DepthBin> got = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, &mask, fixedBins());
  // The same as the 20 clean rows alone.
  Synthetic rest = linearError(20, 0.01);
  const std::vector<DepthBin> want = errorVsDepth(rest.ref, rest.rec, {rest.z, rest.a, {}}, nullptr, fixedBins());
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].pixels, 20);
    EXPECT_NEAR(got[i].relRmse, want[i].relRmse, 1e-9);
  }
  // Coverage 0.5 counts: a surface, not a mix.
  for (float& a : s.a)
    if (a < 0.5f) a = 0.5f;
  EXPECT_EQ(errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, &mask, fixedBins())[0].pixels, 25);
}

// Pixels whose surfaces spread over more than a bin's width (an edge between a near and a far
// surface) are counted in the bin of their mean z but left out of its metrics, however wrong
// they are; up to the bin's width they count.
TEST(DepthError, MixedPixelsAreCountedButLeftOutOfTheMetrics) {
  const double k = 0.01;
  Synthetic s = linearError(30, k);
  std::vector<float> spread(s.z.size(), 0.0f);
  for (int y = 0; y < 10; ++y)  // 10 rows: an edge, and far off in colour
    for (int x = 0; x < 24; ++x) {
      const size_t i = size_t(y) * 24 + size_t(x);
      spread[i] = y < 5 ? 2.001f : 2.0f;  // beyond the 2 mm bins, or just within
      if (y < 5)
        for (int c = 0; c < 3; ++c) s.rec.at(x, y, c) = 10.0f;
    }
  const std::vector<DepthBin> bins = errorVsDepth(s.ref, s.rec, {s.z, s.a, spread}, nullptr, fixedBins());
  for (int i = 0; i < 24; ++i) {
    const DepthBin& b = bins[size_t(i)];
    EXPECT_EQ(b.pixels, 25);
    EXPECT_EQ(b.mixedPixels, 5);
    EXPECT_NEAR(b.relRmse, k * std::abs(b.zCentre), 1e-6) << "bin " << i;
  }
  DepthBinning all = fixedBins();
  all.leaveOutMixed = false;
  const std::vector<DepthBin> kept = errorVsDepth(s.ref, s.rec, {s.z, s.a, spread}, nullptr, all);
  EXPECT_EQ(kept[3].pixels, 30);
  EXPECT_EQ(kept[3].mixedPixels, 0);
  EXPECT_GT(kept[3].relRmse, 1.0);
}

TEST(DepthError, SparseBinsKeepTheirCountWithoutMetrics) {
  const Synthetic s = linearError(19, 0.01);  // 19 pixels per bin: one short of the minimum
  const std::vector<DepthBin> bins = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins());
  for (const DepthBin& b : bins) {
    EXPECT_EQ(b.pixels, 19);
    EXPECT_TRUE(std::isnan(b.relRmse));
    EXPECT_TRUE(std::isnan(b.de2000Mean));
  }
  DepthBinning fewer = fixedBins();
  fewer.minPixels = 19;
  EXPECT_TRUE(std::isfinite(errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fewer)[3].relRmse));
}

TEST(DepthError, DefaultRangeIsTheFirstToNinetyNinthPercentile) {
  // 1000 pixels at z = 0, 0.1, ..., 99.9: the type-7 percentiles are 0.999 and 98.901 (rank
  // p/100 x 999); the pixels outside are left out.
  Image img(1000, 1, {"R", "G", "B"});
  std::fill(img.data.begin(), img.data.end(), 0.5f);
  std::vector<float> z(1000), a(1000, 1.0f);
  for (int i = 0; i < 1000; ++i) z[size_t(i)] = float(0.1 * i);
  const std::vector<DepthBin> bins = errorVsDepth(img, img, {z, a, {}}, nullptr, {});
  ASSERT_EQ(bins.size(), 24u);  // the default count
  EXPECT_NEAR(bins.front().zLo, 0.999, 1e-5);
  EXPECT_NEAR(bins.back().zHi, 98.901, 1e-5);
  int64_t n = 0;
  for (const DepthBin& b : bins) n += b.pixels;
  EXPECT_EQ(n, 1000 - 10 - 10);  // z < 0.999 (0 .. 0.9) and z > 98.901 (99.0 .. 99.9)
  EXPECT_EQ(bins[5].relRmse, 0.0);
}

TEST(DepthError, AFlatSceneIsOneBinAboutItsDepth) {
  Image img(10, 10, {"R", "G", "B"});
  std::fill(img.data.begin(), img.data.end(), 0.5f);
  const std::vector<float> z(100, 5.0f), a(100, 1.0f);
  const std::vector<DepthBin> bins = errorVsDepth(img, img, {z, a, {}}, nullptr, {});
  ASSERT_EQ(bins.size(), 24u);
  EXPECT_NEAR(bins.front().zLo, 4.5, 1e-9);
  EXPECT_NEAR(bins.back().zHi, 5.5, 1e-9);
  int64_t n = 0;
  for (const DepthBin& b : bins) n += b.pixels;
  EXPECT_EQ(n, 100);
  int full = 0;
  for (const DepthBin& b : bins)
    if (b.pixels == 100) {
      ++full;
      EXPECT_TRUE(b.zLo <= 5.0 && 5.0 <= b.zHi);
    }
  EXPECT_EQ(full, 1);
  // No pixel counts: no bins.
  EXPECT_TRUE(errorVsDepth(img, img, {z, std::vector<float>(100, 0.0f), {}}, nullptr, {}).empty());
}

TEST(DepthError, BadInputsAreNamed) {
  const Synthetic s = linearError(4, 0.0);
  std::vector<float> shortZ(s.z.begin(), s.z.end() - 1);
  EXPECT_EQ(expectInputError([&] { (void)errorVsDepth(s.ref, s.rec, {shortZ, s.a, {}}, nullptr); }).key(), "depth");
  EXPECT_EQ(expectInputError([&] { (void)errorVsDepth(s.ref, s.rec, {s.z, shortZ, {}}, nullptr); }).key(), "coverage");
  EXPECT_EQ(expectInputError([&] { (void)errorVsDepth(s.ref, s.rec, {s.z, s.a, shortZ}, nullptr); }).key(),
            "depth_spread");
  DepthBinning b;
  b.count = 0;
  EXPECT_EQ(expectInputError([&] { (void)errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, b); }).key(), "depth_bins");
  b = fixedBins();
  b.maxZ = b.minZ;
  EXPECT_EQ(expectInputError([&] { (void)errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, b); }).key(), "depth_range");
}

// Error / detail: the bin's mean colour painted flat is off by exactly the detail (1); a
// reconstruction off by ref k z is off by |k z| |ref|_rms / detail, the detail computed here in
// two passes; a bin of one colour has no detail to compare with (NaN) while its relative RMSE
// stays finite.
TEST(DepthError, ErrorOverDetailIsOneForTheBinsMeanColourPaintedFlat) {
  const int rows = 35;
  Synthetic s = linearError(rows, 0.01);
  double mean[3] = {0, 0, 0};
  for (int y = 0; y < rows; ++y)
    for (int c = 0; c < 3; ++c) mean[c] += s.ref.at(0, y, c) / double(rows);  // every column alike
  double ref2 = 0.0, detail2 = 0.0;
  for (int y = 0; y < rows; ++y)
    for (int c = 0; c < 3; ++c) {
      const double r = s.ref.at(0, y, c);
      ref2 += r * r / rows, detail2 += (r - mean[c]) * (r - mean[c]) / rows;
    }
  const std::vector<DepthBin> linear = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins());
  for (const DepthBin& b : linear)
    EXPECT_NEAR(b.errorOverDetail, 0.01 * std::abs(b.zCentre) * std::sqrt(ref2 / detail2), 1e-5) << b.zCentre;

  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < s.rec.width; ++x)
      for (int c = 0; c < 3; ++c) s.rec.at(x, y, c) = float(mean[c]);
  for (const DepthBin& b : errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins()))
    EXPECT_NEAR(b.errorOverDetail, 1.0, 1e-5) << b.zCentre;

  Image flat = s.ref;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < flat.width; ++x)
      for (int c = 0; c < 3; ++c) flat.at(x, y, c) = 0.4f;
  const DepthBin b = errorVsDepth(flat, s.rec, {s.z, s.a, {}}, nullptr, fixedBins())[3];
  EXPECT_TRUE(std::isnan(b.errorOverDetail));
  EXPECT_TRUE(std::isfinite(b.relRmse));
}

TEST(DepthError, JsonAndCsvCarryEveryBinWithNaNAsNull) {
  const Synthetic s = linearError(19, 0.01);
  std::vector<DepthBin> bins = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins());
  bins[1].relRmse = 0.25, bins[1].de2000Mean = 3.0, bins[1].errorOverDetail = 0.5;
  const Json j = depthBinsJson(bins);
  ASSERT_EQ(j.size(), 24u);
  EXPECT_TRUE(j[0]["rel_rmse"].is_null());
  EXPECT_EQ(j[1]["rel_rmse"].get<double>(), 0.25);
  EXPECT_EQ(j[1]["de2000_mean"].get<double>(), 3.0);
  EXPECT_EQ(j[1]["pixels"].get<int64_t>(), 19);
  EXPECT_EQ(j[1]["z_lo"].get<double>(), -22.0);
  EXPECT_EQ(j[1]["z_hi"].get<double>(), -20.0);
  const auto rows = depthBinsCsvRows(bins);
  ASSERT_EQ(rows.size(), 24u);
  EXPECT_EQ(rows[0].size(), depthBinsCsvHeader().size());
  EXPECT_EQ(rows[0][4], "0");  // mixed pixels
  EXPECT_EQ(rows[0][5], "nan");
  EXPECT_EQ(depthBinsCsvHeader().back(), "error_over_detail");
  EXPECT_TRUE(j[0]["error_over_detail"].is_null());
  EXPECT_EQ(j[1]["error_over_detail"].get<double>(), 0.5);
  bins[2].mixedPixels = 7;
  EXPECT_EQ(depthBinsJson(bins)[2]["mixed_pixels"].get<int64_t>(), 7);
}

// Two designs of known error, rec = ref + e(z) on every channel: A sharp at z = 10 (e = 0.01
// |z - 10|), B at z = -10. Relative to the lower of the two, A's error is |z - 10| / |z + 10| where
// B is better and 1 where A is, whatever the reference shows: on a reference whose brightness
// changes from depth to depth, each design's relative RMSE changes shape, the ratio does not.
TEST(DepthError, ErrorRelativeToTheLowestDesignCancelsWhatEachDepthHolds) {
  for (double contrast : {0.0, 0.8}) {
    Synthetic s = linearError(23, 0.0);
    Image recA = s.ref, recB = s.ref;
    for (int y = 0; y < s.ref.height; ++y)
      for (int x = 0; x < s.ref.width; ++x) {
        const double z = s.z[size_t(x)], content = 1.0 + contrast * std::sin(0.7 * x);
        for (int ch = 0; ch < 3; ++ch) {
          s.ref.at(x, y, ch) = float(s.ref.at(x, y, ch) * content);
          recA.at(x, y, ch) = s.ref.at(x, y, ch) + float(0.01 * std::abs(z - 10.0));
          recB.at(x, y, ch) = s.ref.at(x, y, ch) + float(0.01 * std::abs(z + 10.0));
        }
      }
    const DepthMap depth{s.z, s.a, {}};
    const auto a = errorVsDepth(s.ref, recA, depth, nullptr, fixedBins());
    const auto b = errorVsDepth(s.ref, recB, depth, nullptr, fixedBins());
    const auto rel = errorRelativeToLowest({a, b});
    ASSERT_EQ(rel.size(), 2u);
    ASSERT_EQ(rel[0].size(), 24u);
    for (size_t k = 0; k < 24; ++k) {
      const double z = a[k].zCentre, ea = std::abs(z - 10.0), eb = std::abs(z + 10.0);
      EXPECT_NEAR(rel[0][k], std::max(1.0, ea / eb), 1e-4) << "z " << z << " contrast " << contrast;
      EXPECT_NEAR(rel[1][k], std::max(1.0, eb / ea), 1e-4) << "z " << z << " contrast " << contrast;
    }
  }
}

TEST(DepthError, ErrorRelativeToTheLowestNeedsTheSameBins) {
  const Synthetic s = linearError(23, 0.01);
  const auto a = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins());
  DepthBinning shifted = fixedBins();
  shifted.minZ = -23.0;
  const auto b = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, shifted);
  EXPECT_EQ(expectInputError([&] { (void)errorRelativeToLowest({a, b}); }).key(), "depth_bins");
  std::vector<DepthBin> fewer = a;
  fewer[3].pixels -= 1;
  EXPECT_EQ(expectInputError([&] { (void)errorRelativeToLowest({a, fewer}); }).key(), "depth_bins");
  // A bin without a metric stays NaN; the one design left there is the lowest.
  std::vector<DepthBin> gap = a;
  gap[5].relRmse = std::numeric_limits<double>::quiet_NaN();
  const auto rel = errorRelativeToLowest({a, gap});
  EXPECT_TRUE(std::isnan(rel[1][5]));
  EXPECT_DOUBLE_EQ(rel[0][5], 1.0);
  EXPECT_DOUBLE_EQ(rel[0][2], 1.0);
  EXPECT_DOUBLE_EQ(rel[1][2], 1.0);
}

TEST(DepthErrorPlot, MarksTheMlaPlaneLAndTheDepthOfFieldBand) {
  const Synthetic s = linearError(30, 0.01);
  const std::vector<DepthBin> bins = errorVsDepth(s.ref, s.rec, {s.z, s.a, {}}, nullptr, fixedBins());
  DepthMarks m;
  m.referencePlaneMm = 30.0;  // beyond the bins: the range grows to show it
  m.referencePlaneLabel = "L = 30 mm";
  m.samplingRangeMm = 100.0;   // wider than the range: clipped to it
  m.depthOfFieldMm = std::pair{27.0, 33.0};  // around L, partly beyond the range: clipped to it
  for (DepthErrorQuantity q :
       {DepthErrorQuantity::RelativeRmse, DepthErrorQuantity::ErrorOverDetail, DepthErrorQuantity::DeltaE2000}) {
    const Plot p = depthErrorPlot({{"0°", bins}, {"H +7°", bins}}, m, q);
    ASSERT_EQ(p.series.size(), 2u);
    ASSERT_EQ(p.markers.size(), 2u);
    EXPECT_EQ(p.markers[0].value, 0.0);
    EXPECT_EQ(p.markers[0].label, "MLA plane");
    EXPECT_EQ(p.markers[1].value, 30.0);
    const PlotFrame f = plotFrame(p);
    EXPECT_LE(f.xMin, -24.0);
    EXPECT_GE(f.xMax, 30.0);
    ASSERT_EQ(p.polygons.size(), 2u);
    for (const PlotPolygon& band : p.polygons)
      for (double x : band.x) EXPECT_TRUE(x >= f.xMin && x <= f.xMax) << x;
    EXPECT_EQ(p.polygons[1].x[0], 27.0);
    // Every value is inside the y range (and the top leaves room above the largest).
    for (const PlotSeries& ser : p.series)
      for (double y : ser.y) EXPECT_LT(y, f.yMax);
  }
  // Linear from 0 while the values stay within a decade; logarithmic when one bin is far above.
  std::vector<DepthBin> even = bins;
  for (size_t i = 0; i < even.size(); ++i) even[i].relRmse = 0.2 + 0.01 * double(i);
  const Plot linPlot = depthErrorPlot({{"0°", even}}, m, DepthErrorQuantity::RelativeRmse);
  EXPECT_FALSE(linPlot.y.log);
  EXPECT_EQ(plotFrame(linPlot).yMin, 0.0);
  even[5].relRmse = 100.0;
  const Plot logPlot = depthErrorPlot({{"0°", even}}, m, DepthErrorQuantity::RelativeRmse);
  EXPECT_TRUE(logPlot.y.log);
  const PlotFrame lf = plotFrame(logPlot);
  for (double y : logPlot.series[0].y) EXPECT_TRUE(y > lf.yMin && y < lf.yMax) << y;
  // Without L or a band, only the MLA plane.
  const Plot bare = depthErrorPlot({{"0°", bins}}, DepthMarks{}, DepthErrorQuantity::RelativeRmse);
  EXPECT_EQ(bare.markers.size(), 1u);
  EXPECT_TRUE(bare.polygons.empty());
  // The figure: the three plots, one above the other. Here the legend has to go outside the upper
  // one (the marks fill its corners): the figure widens by the legend (and a font size' gap)
  // rather than the plots narrowing; without marks the legend fits inside and the figure is as
  // wide as a plot.
  const Plot upper = depthErrorPlot({{"0°", bins}}, m, DepthErrorQuantity::RelativeRmse);
  const PlotFrame uf = plotFrame(upper);
  ASSERT_TRUE(uf.legendOutside);
  const Image fig = depthErrorFigure({{"0°", bins}}, m);
  EXPECT_EQ(fig.width, bare.width + int(std::ceil(uf.legend.x1 - uf.legend.x0 + upper.fontSize)));
  EXPECT_EQ(fig.height, 3 * bare.height);
  ASSERT_FALSE(plotFrame(bare).legendOutside);
  EXPECT_EQ(depthErrorFigure({{"0°", bins}}, DepthMarks{}).width, bare.width);
}
