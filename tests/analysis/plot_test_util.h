#pragma once
// Helpers for the plot tests: dark pixels in a box, and where a plot's data is drawn.
#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/plot.h"

namespace plot_test {

// Pixels darker than `below` (in any channel) inside [x0, x1) x [y0, y1).
inline int darkIn(const inim::Image& img, double x0, double y0, double x1, double y1, float below = 0.5f) {
  int n = 0;
  for (int y = std::max(0, int(std::floor(y0))); y < std::min(img.height, int(std::ceil(y1))); ++y)
    for (int x = std::max(0, int(std::floor(x0))); x < std::min(img.width, int(std::ceil(x1))); ++x)
      n += std::min({img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)}) < below;
  return n;
}

// The pixels where `p` draws its data (layers, markers, annotations): those that differ
// between the plot without a legend and the same axes with nothing on them. The axes keep
// the plot's frame (its ranges fixed to what plotFrame chose).
inline std::vector<bool> dataPixels(const inim::Plot& p) {
  const inim::PlotFrame f = inim::plotFrame(p);
  inim::Plot bare;
  bare.width = p.width, bare.height = p.height;
  bare.title = p.title, bare.fontSize = p.fontSize, bare.grid = p.grid;
  bare.x = p.x, bare.y = p.y;
  bare.x.min = f.xMin, bare.x.max = f.xMax, bare.y.min = f.yMin, bare.y.max = f.yMax;
  inim::Plot noLegend = p;
  noLegend.legend = false;
  const inim::Image a = inim::renderPlot(noLegend), b = inim::renderPlot(bare);
  std::vector<bool> ink(size_t(a.width) * size_t(a.height), false);
  for (size_t i = 0; i < ink.size(); ++i)
    for (int c = 0; c < 3; ++c) ink[i] = ink[i] || a.data[3 * i + size_t(c)] != b.data[3 * i + size_t(c)];
  return ink;
}

}  // namespace plot_test
