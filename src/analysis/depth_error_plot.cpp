// The figure of analysis/depth_error.h: error against depth with the MLA plane, L and the
// depth-of-field band marked.
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/depth_error.h"

namespace inim {

namespace {

double binValue(const DepthBin& b, DepthErrorQuantity q) {
  switch (q) {
    case DepthErrorQuantity::RelativeRmse: return b.relRmse;
    case DepthErrorQuantity::ErrorOverDetail: return b.errorOverDetail;
    case DepthErrorQuantity::DeltaE2000: return b.de2000Mean;
  }
  return 0.0;
}

struct QuantityText {
  const char* name;   // within a figure's panel title
  const char* title;  // a plot's own title
  const char* axis;
};
QuantityText quantityText(DepthErrorQuantity q) {
  switch (q) {
    case DepthErrorQuantity::RelativeRmse:
      return {"relative RMSE", "Relative RMSE against depth", "relative RMSE (linear RGB)"};
    case DepthErrorQuantity::ErrorOverDetail:
      return {"error / detail", "Error / detail against depth", "RMSE / detail (1: flat mean colour)"};
    case DepthErrorQuantity::DeltaE2000:
      return {"mean CIEDE2000", "Mean CIEDE2000 against depth", "mean ΔE2000"};
  }
  return {"", "", ""};
}

// The x range: every bin and the marked planes, a little padding on both sides.
std::pair<double, double> zRange(const std::vector<DepthErrorCurve>& curves, const DepthMarks& m) {
  double lo = 0.0, hi = 0.0;  // the MLA plane is always shown
  for (const DepthErrorCurve& c : curves)
    for (const DepthBin& b : c.bins) lo = std::min(lo, b.zLo), hi = std::max(hi, b.zHi);
  if (m.referencePlaneMm && std::isfinite(*m.referencePlaneMm))
    lo = std::min(lo, *m.referencePlaneMm), hi = std::max(hi, *m.referencePlaneMm);
  if (!(hi > lo)) lo -= 1.0, hi += 1.0;
  const double pad = 0.03 * (hi - lo);
  return {lo - pad, hi + pad};
}

// The y range: 0 to a little above the largest value (room for the marker labels and the
// legend); a log axis when the values spread over more than a decade (a few dark bins, where a
// relative error explodes, would flatten every other curve).
struct YRange {
  double lo = 0.0, hi = 1.0;
  bool log = false;
};
YRange yRange(const std::vector<DepthErrorCurve>& curves, DepthErrorQuantity q) {
  double top = 0.0, bottom = std::numeric_limits<double>::infinity();
  for (const DepthErrorCurve& c : curves)
    for (const DepthBin& b : c.bins)
      if (const double v = binValue(b, q); std::isfinite(v)) {
        top = std::max(top, v);
        if (v > 0.0) bottom = std::min(bottom, v);
      }
  if (!(top > 0.0)) return {};
  if (top > 10.0 * bottom) return {0.7 * bottom, 2.0 * top, true};
  return {0.0, 1.3 * top, false};
}

void addMarks(Plot& p, const DepthMarks& m, double zLo, double zHi, double yLo, double yHi) {
  const Vec3 grey(0.35f, 0.35f, 0.35f), dark(0.1f, 0.1f, 0.1f);
  auto addBand = [&](double lo, double hi, const std::string& name, const Vec3& colour) {
    const double a = std::max(zLo, lo), b = std::min(zHi, hi);
    if (!(b > a)) return;
    PlotPolygon band;
    band.name = name;
    band.x = {a, b, b, a};
    band.y = {yLo, yLo, yHi, yHi};
    band.color = colour;
    band.alpha = 0.25;
    band.edgeWidth = 0.0;
    p.polygons.push_back(band);
  };
  if (m.samplingRangeMm > 0.0)
    addBand(-m.samplingRangeMm, m.samplingRangeMm, m.samplingRangeLabel, Vec3(0.55f, 0.7f, 0.9f));
  if (m.depthOfFieldMm)
    addBand(m.depthOfFieldMm->first, m.depthOfFieldMm->second, m.depthOfFieldLabel, Vec3(0.95f, 0.6f, 0.2f));
  p.markers.push_back({0.0, "MLA plane", dark, 0.0});
  if (m.referencePlaneMm && std::isfinite(*m.referencePlaneMm))
    p.markers.push_back({*m.referencePlaneMm, m.referencePlaneLabel, grey, 6.0});
}

}  // namespace

Plot depthErrorPlot(const std::vector<DepthErrorCurve>& curves, const DepthMarks& marks, DepthErrorQuantity q) {
  Plot p;
  p.width = 900;
  p.height = 420;
  const QuantityText text = quantityText(q);
  p.title = text.title;
  p.x.title = "scene depth z (mm, display frame; > 0 toward the viewer)";
  p.y.title = text.axis;
  const auto [zLo, zHi] = zRange(curves, marks);
  const YRange y = yRange(curves, q);
  p.x.min = zLo, p.x.max = zHi;
  p.y.min = y.lo, p.y.max = y.hi;
  p.y.log = y.log;
  if (y.log) p.y.title += ", log scale";
  addMarks(p, marks, zLo, zHi, y.lo, y.hi);
  for (size_t i = 0; i < curves.size(); ++i) {
    PlotSeries s;
    s.name = curves[i].name;
    for (const DepthBin& b : curves[i].bins) {
      s.x.push_back(b.zCentre);
      s.y.push_back(binValue(b, q));
    }
    s.color = plotPalette(int(i));
    s.markerRadius = 3.0;
    p.series.push_back(std::move(s));
  }
  return p;
}

Image depthErrorFigure(const std::vector<DepthErrorCurve>& curves, const DepthMarks& marks, const std::string& title) {
  std::vector<Plot> panels;
  for (DepthErrorQuantity q :
       {DepthErrorQuantity::RelativeRmse, DepthErrorQuantity::ErrorOverDetail, DepthErrorQuantity::DeltaE2000}) {
    panels.push_back(depthErrorPlot(curves, marks, q));
    panels.back().title = title + ": " + quantityText(q).name + (panels.size() > 1 ? " (curves and marks as above)" : "");
    panels.back().legend = panels.size() == 1;
  }
  if (const PlotFrame f = plotFrame(panels[0]); f.legendOutside)  // the figure widens for it, not the plots narrow
    for (Plot& p : panels) p.width += int(std::ceil(f.legend.x1 - f.legend.x0 + p.fontSize));
  std::vector<Plot*> aligned;
  for (Plot& p : panels) aligned.push_back(&p);
  alignPlotAreas(aligned);

  std::vector<Image> images;
  int width = 0, height = 0;
  for (const Plot& p : panels) {
    images.push_back(renderPlot(p));
    width = std::max(width, images.back().width), height += images.back().height;
  }
  Image out(width, height, {"R", "G", "B"});
  std::fill(out.data.begin(), out.data.end(), 1.0f);
  int top = 0;
  for (const Image& a : images) {
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c) out.at(x, top + y, c) = a.at(x, y, c);
    top += a.height;
  }
  return out;
}

}  // namespace inim
