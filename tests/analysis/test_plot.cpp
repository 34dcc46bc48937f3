// Plots: the data-to-pixel transform (linear and log axes), ticks, rendering at the requested
// size with each data point where the transform says, PNG output, and CSV text.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/plot.h"
#include "core/error.h"

namespace fs = std::filesystem;
using namespace inim;

TEST(Plot, CoordinateTransformLinear) {
  Plot p;
  p.width = 640, p.height = 400;
  p.x.min = -2.0, p.x.max = 6.0;
  p.y.min = 10.0, p.y.max = 20.0;
  PlotFrame f = plotFrame(p);
  EXPECT_EQ(f.xMin, -2.0);
  EXPECT_EQ(f.xMax, 6.0);
  EXPECT_GT(f.right, f.left);
  EXPECT_GT(f.bottom, f.top);
  EXPECT_LE(f.right, 640);
  EXPECT_LE(f.bottom, 400);
  // Corners and an interior point.
  EXPECT_DOUBLE_EQ(f.pixelX(-2.0), f.left);
  EXPECT_DOUBLE_EQ(f.pixelX(6.0), f.right);
  EXPECT_DOUBLE_EQ(f.pixelY(10.0), f.bottom);  // y grows upward on screen
  EXPECT_DOUBLE_EQ(f.pixelY(20.0), f.top);
  const glm::dvec2 q = f.toPixel(0.0, 17.5);
  EXPECT_NEAR(q.x, f.left + 0.25 * (f.right - f.left), 1e-9);
  EXPECT_NEAR(q.y, f.bottom - 0.75 * (f.bottom - f.top), 1e-9);
}

TEST(Plot, CoordinateTransformLog) {
  Plot p;
  p.x.log = true;
  p.y.log = true;
  p.series.push_back({"rmse", {0.5, 3.0, 40.0}, {0.02, 0.004, 0.0011}});
  PlotFrame f = plotFrame(p);
  EXPECT_DOUBLE_EQ(f.xMin, 0.1);  // widened to whole decades
  EXPECT_DOUBLE_EQ(f.xMax, 100.0);
  EXPECT_DOUBLE_EQ(f.yMin, 0.001);
  EXPECT_DOUBLE_EQ(f.yMax, 0.1);
  EXPECT_NEAR(f.pixelX(1.0), f.left + (f.right - f.left) / 3.0, 1e-9);
  EXPECT_NEAR(f.pixelY(0.01), 0.5 * (f.top + f.bottom), 1e-9);
  ASSERT_EQ(f.xTicks.size(), 4u);
  EXPECT_DOUBLE_EQ(f.xTicks[0], 0.1);
  EXPECT_DOUBLE_EQ(f.xTicks[3], 100.0);
}

TEST(Plot, AutoRangeWidensToTicks) {
  Plot p;
  p.series.push_back({"a", {0.3, 4.0, 9.7}, {-1.2, 0.5, 3.3}});
  p.markers.push_back({10.4, "L"});
  PlotFrame f = plotFrame(p);
  EXPECT_LE(f.xMin, 0.3);
  EXPECT_GE(f.xMax, 10.4);  // markers are inside the range
  EXPECT_LE(f.yMin, -1.2);
  EXPECT_GE(f.yMax, 3.3);
  for (double t : f.xTicks) EXPECT_TRUE(t >= f.xMin - 1e-12 && t <= f.xMax + 1e-12);
  EXPECT_DOUBLE_EQ(f.xTicks.front(), f.xMin);
  EXPECT_DOUBLE_EQ(f.xTicks.back(), f.xMax);
}

TEST(Plot, NiceTicksAndLabels) {
  std::vector<double> t = niceTicks(0.0, 1.0, 5);
  ASSERT_EQ(t.size(), 6u);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], 0.2 * double(i), 1e-12);
  EXPECT_DOUBLE_EQ(niceStep(-3.2, 7.9, 8), 2.0);
  t = niceTicks(-3.2, 7.9, 8);
  EXPECT_DOUBLE_EQ(t.front(), -2.0);
  EXPECT_DOUBLE_EQ(t.back(), 6.0);
  EXPECT_EQ(formatTick(0.4, 0.2), "0.4");
  EXPECT_EQ(formatTick(15.0, 5.0), "15");
  EXPECT_EQ(formatTick(0.25, 0.05), "0.25");
  EXPECT_EQ(formatTick(0.0, 0.1), "0");
  EXPECT_EQ(formatTick(2e-6, 1e-6), "2e-06");
  std::vector<double> lt = logTicks(1.0, 10.0);  // one decade: 1, 2, 5, 10
  ASSERT_EQ(lt.size(), 4u);
  EXPECT_DOUBLE_EQ(lt[1], 2.0);
}

TEST(Plot, RendersPointsWhereTheTransformSays) {
  Plot p;
  p.width = 500, p.height = 360;
  p.title = "sharpness vs depth";
  p.x.title = "depth (mm)";
  p.y.title = "sharpness";
  p.x.min = 0.0, p.x.max = 40.0;
  p.y.min = 0.0, p.y.max = 1.0;
  p.legend = false;
  p.grid = false;
  const Vec3 red(0.9f, 0.1f, 0.1f), blue(0.1f, 0.2f, 0.9f);
  PlotSeries a{"measured", {5.0, 15.0, 25.0}, {0.2, 0.8, 0.4}};
  a.color = red;
  a.line = false;
  a.markerRadius = 4.0;
  PlotSeries b{"model", {10.0, 30.0}, {0.5, 0.3}};
  b.color = blue;
  b.line = false;
  p.series = {a, b};
  PlotMarker m{19.0, "L = 19 mm"};
  m.color = Vec3(0.0f, 0.6f, 0.0f);
  m.dash = 0.0;
  p.markers.push_back(m);
  Image img = renderPlot(p);
  EXPECT_EQ(img.width, 500);
  EXPECT_EQ(img.height, 360);
  const PlotFrame f = plotFrame(p);
  auto colourAt = [&](glm::dvec2 q) {
    const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
    return Vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
  };
  for (size_t k = 0; k < a.x.size(); ++k) {
    const Vec3 c = colourAt(f.toPixel(a.x[k], a.y[k]));
    EXPECT_NEAR(c.x, red.x, 1e-6);
    EXPECT_NEAR(c.y, red.y, 1e-6);
    EXPECT_NEAR(c.z, red.z, 1e-6);
  }
  for (size_t k = 0; k < b.x.size(); ++k) EXPECT_NEAR(colourAt(f.toPixel(b.x[k], b.y[k])).z, blue.z, 1e-6);
  // The vertical marker line at x = 19.
  const int mx = int(std::floor(f.pixelX(19.0)));
  const int my = int(f.bottom) - 5;
  EXPECT_NEAR(img.at(mx, my, 1), 0.6f, 1e-6);
  // Outside the plot area the background is white (top-right corner).
  EXPECT_EQ(img.at(499, 0, 0), 1.0f);
  // Writes a PNG of the requested size.
  const fs::path dir = fs::temp_directory_path() / ("inim_test_plot_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "plot.png").string();
  writePlot(p, file);
  Image back = readImage(file);
  EXPECT_EQ(back.width, 500);
  EXPECT_EQ(back.height, 360);
  fs::remove_all(dir);
}

TEST(Plot, LinesBreakAtNonFiniteValuesAndLegendDraws) {
  Plot p;
  p.x.min = 0.0, p.x.max = 10.0;
  p.y.min = 0.0, p.y.max = 10.0;
  PlotSeries s{"a", {1, 2, 3, 4, 5}, {1, 2, std::nan(""), 4, 5}};
  s.markers = false;
  s.color = Vec3(0.0f);
  p.series = {s};
  Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  // On the segment 1 -> 2 the line is drawn; between 2 and 4 (across the gap) it is not.
  const glm::dvec2 on = f.toPixel(1.5, 1.5), off = f.toPixel(3.0, 3.0);
  EXPECT_LT(img.at(int(on.x), int(on.y), 0), 0.5f);
  EXPECT_GT(img.at(int(off.x), int(off.y), 0), 0.8f);
}

TEST(Plot, BadInput) {
  Plot p;
  p.series.push_back({"bad", {1, 2, 3}, {1, 2}});
  EXPECT_THROW(plotFrame(p), InputError);
  Plot q;
  q.x.min = 3.0, q.x.max = 1.0;
  EXPECT_THROW(plotFrame(q), InputError);
  Plot r;
  r.x.log = true;
  r.x.min = -1.0;
  EXPECT_THROW(plotFrame(r), InputError);
  // Empty plots and single points are fine.
  Plot e;
  EXPECT_NO_THROW(renderPlot(e));
  e.series.push_back({"one", {2.0}, {2.0}});
  EXPECT_NO_THROW(renderPlot(e));
  const PlotFrame f = plotFrame(e);
  EXPECT_LT(f.xMin, 2.0);
  EXPECT_GT(f.xMax, 2.0);
}

TEST(Csv, QuotesAndNumbers) {
  EXPECT_EQ(csvField("plain"), "plain");
  EXPECT_EQ(csvField("a,b"), "\"a,b\"");
  EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csvNumber(0.1), "0.1");
  EXPECT_EQ(csvNumber(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(csvNumber(std::nan("")), "nan");
  EXPECT_EQ(csvText({"view", "psnr_db"}, {{"0°", "31.5"}, {"+7° H, left", csvNumber(29.25)}}),
            "view,psnr_db\n0°,31.5\n\"+7° H, left\",29.25\n");
  const fs::path dir = fs::temp_directory_path() / ("inim_test_csv_" + std::to_string(getpid()));
  fs::create_directories(dir);
  writeCsv((dir / "m.csv").string(), {"a"}, {{"1"}, {"2"}});
  std::ifstream in(dir / "m.csv");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "a\n1\n2\n");
  fs::remove_all(dir);
}
