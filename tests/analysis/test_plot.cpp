// Plots: the data-to-pixel transform (linear and log axes), ticks, rendering at the requested
// size with each data point where the transform says, tick labels and titles where they
// belong, PNG output, determinism, and CSV text. Legend placement and the other layers:
// test_plot_legend.cpp, test_plot_layers.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "analysis/plot.h"
#include "analysis/plot_test_util.h"
#include "core/error.h"
#include "draw/text.h"

namespace fs = std::filesystem;
using namespace inim;

using plot_test::darkIn;

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
  // The inverse.
  EXPECT_NEAR(f.dataX(q.x), 0.0, 1e-9);
  EXPECT_NEAR(f.dataY(q.y), 17.5, 1e-9);
  // The plot area is in whole pixels (crisp frame lines).
  EXPECT_EQ(f.left, std::floor(f.left));
  EXPECT_EQ(f.right, std::floor(f.right));
  EXPECT_EQ(f.top, std::floor(f.top));
  EXPECT_EQ(f.bottom, std::floor(f.bottom));
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
  EXPECT_NEAR(f.dataX(f.pixelX(3.0)), 3.0, 1e-9);
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
  // 8-bit colour levels: within half a level of the colour asked for.
  const float level = 0.5f / 255.0f + 1e-6f;
  for (size_t k = 0; k < a.x.size(); ++k) {
    const Vec3 c = colourAt(f.toPixel(a.x[k], a.y[k]));
    EXPECT_NEAR(c.x, red.x, level);
    EXPECT_NEAR(c.y, red.y, level);
    EXPECT_NEAR(c.z, red.z, level);
  }
  for (size_t k = 0; k < b.x.size(); ++k) EXPECT_NEAR(colourAt(f.toPixel(b.x[k], b.y[k])).z, blue.z, level);
  // A marker's disc reaches its radius and no further (antialiased at the rim).
  const glm::dvec2 c0 = f.toPixel(a.x[0], a.y[0]);
  EXPECT_NEAR(colourAt(c0 + glm::dvec2(2.5, 0.0)).y, red.y, level);
  EXPECT_EQ(colourAt(c0 + glm::dvec2(6.0, 0.0)).y, 1.0f);
  // The vertical marker line at x = 19: one crisp column.
  const int mx = int(std::floor(f.pixelX(19.0)));
  const int my = int(f.bottom) - 5;
  EXPECT_NEAR(img.at(mx, my, 1), 0.6f, level);
  EXPECT_NEAR(img.at(mx, my, 0), 0.0f, level);
  EXPECT_EQ(img.at(mx - 1, my, 0), 1.0f);
  EXPECT_EQ(img.at(mx + 1, my, 0), 1.0f);
  // Outside the plot area the background is white (top-right corner).
  EXPECT_EQ(img.at(499, 0, 0), 1.0f);
  // Writes a PNG of the requested size, with the same pixels.
  const fs::path dir = fs::temp_directory_path() / ("inim_test_plot_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "plot.png").string();
  writePlot(p, file);
  Image back = readImage(file);
  EXPECT_EQ(back.width, 500);
  EXPECT_EQ(back.height, 360);
  ASSERT_EQ(back.data.size(), img.data.size());
  int differ = 0;
  for (size_t i = 0; i < img.data.size(); ++i) differ += std::lround(back.data[i] * 255.0f) != std::lround(img.data[i] * 255.0f);
  EXPECT_EQ(differ, 0);
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
  // The legend: a box inside the plot area holding the name and a sample of the line.
  ASSERT_FALSE(f.legend.empty());
  EXPECT_FALSE(f.legendOutside);
  EXPECT_GE(f.legend.x0, f.left);
  EXPECT_LE(f.legend.x1, f.right);
  EXPECT_GT(darkIn(img, f.legend.x0 + 2, f.legend.y0 + 2, f.legend.x1 - 2, f.legend.y1 - 2, 0.3f), 20);
}

TEST(Plot, TickLabelsAndTitlesWhereTheyBelong) {
  Plot p;
  p.width = 640, p.height = 420;
  p.x.min = 0.0, p.x.max = 10.0;
  p.y.min = 0.0, p.y.max = 1.0;
  p.title = "Brightness vs angle";
  p.x.title = "angle (deg)";
  p.y.title = "brightness";
  const Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  ASSERT_GE(f.xTicks.size(), 3u);
  ASSERT_GE(f.yTicks.size(), 3u);
  const double th = 13.0 * 1.3;  // about one line of tick labels
  // Under every x tick, a label; between two labels (halfway between ticks), none.
  for (size_t i = 0; i < f.xTicks.size(); ++i) {
    const double x = f.pixelX(f.xTicks[i]);
    EXPECT_GT(darkIn(img, x - 6, f.bottom + 4, x + 6, f.bottom + 4 + th), 5) << "x tick " << f.xTicks[i];
    if (i > 0) {
      const double mid = 0.5 * (x + f.pixelX(f.xTicks[i - 1]));
      EXPECT_EQ(darkIn(img, mid - 3, f.bottom + 4, mid + 3, f.bottom + 4 + th), 0) << "between x ticks";
    }
  }
  // Left of every y tick, a label, vertically centred on it.
  for (double t : f.yTicks) {
    const double y = f.pixelY(t);
    EXPECT_GT(darkIn(img, f.left - 40, y - 5, f.left - 4, y + 5), 5) << "y tick " << t;
  }
  // The title above the plot area, the x title below the tick labels, the y title at the left
  // edge (turned: taller than wide).
  EXPECT_GT(darkIn(img, f.left, 0, f.right, f.top - 4), 50);
  EXPECT_GT(darkIn(img, f.left, f.bottom + 4 + th, f.right, p.height), 40);
  int yx0 = p.width, yx1 = 0, yy0 = p.height, yy1 = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < 24; ++x)
      if (img.at(x, y, 0) < 0.5f) yx0 = std::min(yx0, x), yx1 = std::max(yx1, x), yy0 = std::min(yy0, y), yy1 = std::max(yy1, y);
  ASSERT_LT(yx0, yx1);
  EXPECT_GT(yy1 - yy0, 3 * (yx1 - yx0));
  EXPECT_NEAR(0.5 * (yy0 + yy1), 0.5 * (f.top + f.bottom), 10.0);
  // Nothing inside the empty plot area but the grid (light grey).
  EXPECT_EQ(darkIn(img, f.left + 1, f.top + 1, f.right - 1, f.bottom - 1, 0.8f), 0);
}

TEST(Plot, CategoryAxisNamesItsTicksAndTurnsCrowdedNames) {
  Plot p;
  p.width = 640, p.height = 420;
  p.x.categories = {"red", "green", "blue"};
  p.bars.push_back({"", {0.0, 1.0, 2.0}, {1.0, 2.0, 3.0}});
  const PlotFrame f = plotFrame(p);
  EXPECT_EQ(f.xMin, -0.5);
  EXPECT_EQ(f.xMax, 2.5);
  ASSERT_EQ(f.xTicks, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_FALSE(f.xLabelsUp);
  const Image img = renderPlot(p);
  const double th = 13.0 * 1.3;
  for (double t : f.xTicks) {
    const double x = f.pixelX(t);
    const double w = draw::measureText(p.x.categories[size_t(t)], {13.0}).width;
    EXPECT_GT(darkIn(img, x - 0.5 * w, f.bottom + 4, x + 0.5 * w, f.bottom + 4 + th), 10) << t;
  }
  // No grid line up from a category's tick (above the lowest bar, between horizontal ones).
  const double yMid = 0.5 * (f.yTicks[f.yTicks.size() - 2] + f.yTicks.back());
  EXPECT_EQ(darkIn(img, f.pixelX(0.0) - 2, f.pixelY(yMid) - 2, f.pixelX(0.0) + 2, f.pixelY(yMid) + 2, 0.99f), 0);

  // Many long names do not fit side by side: turned to read upwards, each in a column under
  // its tick ending at the axis, the plot area shorter for them.
  Plot q = p;
  q.x.categories.clear();
  q.bars[0].x.clear(), q.bars[0].y.clear();
  for (int i = 0; i < 24; ++i) {
    std::string name = "patch number ";
    q.x.categories.push_back(name += std::to_string(i));
    q.bars[0].x.push_back(i), q.bars[0].y.push_back(1.0);
  }
  const PlotFrame g = plotFrame(q);
  EXPECT_TRUE(g.xLabelsUp);
  EXPECT_LT(g.bottom, f.bottom - 40);
  const Image qi = renderPlot(q);
  const double len = draw::measureText(q.x.categories[5], {13.0}).width;
  const double x5 = g.pixelX(5.0), x55 = g.pixelX(5.5);
  EXPECT_GT(darkIn(qi, x5 - 6, g.bottom + 4, x5 + 6, g.bottom + 4 + 0.3 * len), 10);
  EXPECT_GT(darkIn(qi, x5 - 6, g.bottom + 4 + 0.7 * len, x5 + 6, g.bottom + 4 + len), 10);
  EXPECT_EQ(darkIn(qi, x55 - 1, g.bottom + 4, x55 + 1, g.bottom + 4 + len), 0);

  // Categories on the y axis or on a log x axis are refused.
  Plot y;
  y.y.categories = {"a"};
  EXPECT_THROW(plotFrame(y), InputError);
  Plot lg;
  lg.x.categories = {"a"};
  lg.x.log = true;
  EXPECT_THROW(plotFrame(lg), InputError);
}

TEST(Plot, LongTitleStaysInsideTheImage) {
  Plot p;
  p.width = 420, p.height = 300;
  p.y.min = 1000.0, p.y.max = 100000.0;  // wide tick labels: the plot area's centre is right of the image's
  p.y.title = "counts";
  p.title = "A long title, nearly as wide as the image";
  const double margin = std::round(0.7 * p.fontSize);
  const double w = draw::measureText(p.title, {std::round(1.25 * p.fontSize), true}).width;
  const PlotFrame f = plotFrame(p);
  // It fits in the image, but not centred over the plot area.
  ASSERT_LT(w, p.width - 2 * margin);
  ASSERT_GT(0.5 * (f.left + f.right) + 0.5 * w, p.width - margin);
  const Image img = renderPlot(p);
  EXPECT_GT(darkIn(img, 0, 0, p.width, f.top - 4), 100);
  EXPECT_EQ(darkIn(img, p.width - margin + 2, 0, p.width, f.top - 4), 0);
}

// A title wider than the image is broken at spaces into lines that each fit; the plot area
// moves down by the added lines.
TEST(Plot, TitleWiderThanTheImageWrapsIntoLinesThatFit) {
  Plot p;
  p.width = 360, p.height = 300;
  p.title = "Short";
  const PlotFrame one = plotFrame(p);
  p.title = "Error against depth at 0 degrees, against the band-limited reference: default scene";
  const double margin = std::round(0.7 * p.fontSize);
  const draw::Font titleFont{std::round(1.25 * p.fontSize), true};
  ASSERT_GT(draw::measureText(p.title, titleFont).width, 2.0 * (p.width - 2 * margin));  // three lines at least
  const PlotFrame f = plotFrame(p);
  const double line = draw::measureText("Ag", titleFont).height;
  const double lines = std::round((f.top - one.top) / line) + 1;
  EXPECT_NEAR(f.top - one.top, (lines - 1) * line, 1.0);
  EXPECT_GE(lines, 3);
  const Image img = renderPlot(p);
  // Ink on every line, none beyond the margins.
  for (int k = 0; k < int(lines); ++k)
    EXPECT_GT(darkIn(img, margin, margin + k * line, p.width - margin, margin + (k + 1) * line), 30) << "line " << k;
  EXPECT_EQ(darkIn(img, 0, 0, margin - 2, f.top - 4), 0);
  EXPECT_EQ(darkIn(img, p.width - margin + 2, 0, p.width, f.top - 4), 0);
}

TEST(Plot, RenderingIsDeterministicAcrossThreads) {
  Plot p;
  p.title = "ψ/2 ± 0.5°";
  p.x.title = "λ (nm)";
  p.series.push_back({"a", {0.0, 1.3, 2.9, 4.1}, {0.2, 0.9, 0.4, 0.7}});
  p.series.push_back({"b", {0.5, 2.0, 3.5}, {0.8, 0.1, 0.5}});
  p.series[1].dash = 5.0;
  p.markers.push_back({2.2, "L"});
  const Image ref = renderPlot(p);
  std::vector<Image> out(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) threads.emplace_back([&, t] { out[size_t(t)] = renderPlot(p); });
  for (auto& t : threads) t.join();
  for (const Image& img : out) EXPECT_EQ(img.data, ref.data);
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
  Plot h;
  h.heatMap = PlotHeatMap{3, 2, {1, 2, 3, 4, 5}};
  EXPECT_THROW(plotFrame(h), InputError);
  Plot b;
  b.bars.push_back({"bars", {1, 2}, {1}});
  EXPECT_THROW(plotFrame(b), InputError);
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
