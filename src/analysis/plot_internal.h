#pragma once
// Internal to the plot implementation (plot_*.cpp): sizes derived from the font size, the
// colours of layers, drawing of the layers, and the legend.
#include <string>
#include <vector>

#include "analysis/plot.h"
#include "draw/canvas.h"

namespace inim::plotimpl {

// Fonts and spacing of a plot, in px, all following Plot::fontSize.
struct Style {
  draw::Font tick, axisTitle, title;
  double margin, tickLength, gap;
  explicit Style(const Plot& p);
};

// The plot's title in lines that each fit the image's width between the margins (broken at
// spaces; a single word wider than that stays whole). Empty for no title.
std::vector<std::string> titleLines(const Plot& p, const Style& st);
// The height of one title line; the title takes its lines and a gap above the plot area
// (titleHeight, 0 without a title).
double titleLineHeight(const Style& st);
double titleHeight(const Plot& p, const Style& st);

bool usable(double v, bool log);  // finite, and > 0 on a log axis
// The label of tick t among `ticks` (decimals from their spacing; each its own on a log axis).
std::string tickLabel(const std::vector<double>& ticks, bool log, double t);
// The label of x tick t: its category name, else as tickLabel.
std::string xTickLabel(const Plot& p, const PlotFrame& f, double t);

// Default colours: series by index, then polygons, then bars, along one palette.
Vec3 seriesColor(const Plot& p, size_t i);
Vec3 polygonColor(const Plot& p, size_t i);
Vec3 barsColor(const Plot& p, size_t i);
// A bar set's width in x units.
double barWidth(const PlotBars& b);
// The heat map's colour of a value, given the colour range.
Vec3 heatColor(const PlotHeatMap& h, double v, double cMin, double cMax);

// Everything drawn inside the plot area (clipped to it): heat map, polygons, bars, marker
// lines, series, annotations and marker labels. Also drawn on a transparent canvas to find
// where the data is, for the legend.
void drawContent(draw::Canvas& cv, const Plot& p, const PlotFrame& f);
// One marker of a series (radius as PlotSeries::markerRadius), also in the legend.
void drawMarker(draw::Canvas& cv, MarkerShape shape, glm::dvec2 centre, double radius, const Vec3& color);
// How far a marker of this radius reaches from its centre, px.
double markerReach(double radius);

// The legend's size for the plot's named layers; zero without any.
glm::dvec2 legendSize(const Plot& p);
// The first box of size `size` inside `area` (corners first, then the nearest place to a
// corner) with no ink within `clearance` px, on a w x h mask; empty when there is none.
PixelBox freeBox(const std::vector<uint8_t>& ink, int w, int h, const PixelBox& area, glm::dvec2 size,
                 double clearance);
void drawLegend(draw::Canvas& cv, const Plot& p, const PlotFrame& f);

}  // namespace inim::plotimpl
