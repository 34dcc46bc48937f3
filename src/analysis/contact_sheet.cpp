#include "analysis/contact_sheet.h"

#include <algorithm>
#include <cmath>

#include "analysis/colormap.h"
#include "analysis/metrics.h"
#include "core/parallel.h"
#include "draw/text.h"
#include "spectral/color.h"

namespace inim {

namespace {

draw::Font titleFont(const ContactSheetOptions& o) { return {o.titleSize}; }
draw::Font headingFont(const ContactSheetOptions& o) { return {o.headingSize}; }
// Text boxes in whole pixels.
int textWidth(const std::string& s, const draw::Font& f) { return s.empty() ? 0 : int(std::ceil(draw::measureText(s, f).width)); }
int lineHeight(const draw::Font& f) { return int(std::ceil(draw::measureText("Ag", f).height)); }

struct CellSize {
  bool used = false;
  int w = 0, h = 0;     // image
  int titleW = 0;       // title text width (0 for none)
};

// The image size a cell shows after the optional downscale.
void displaySize(const Image& img, const ContactSheetOptions& opt, int& w, int& h) {
  w = img.width;
  h = img.height;
  if (opt.maxImageWidth > 0 && w > opt.maxImageWidth) {
    h = std::max(1, int(std::lround(double(h) * opt.maxImageWidth / w)));
    w = opt.maxImageWidth;
  }
}

SheetLayout layoutFromSizes(const std::vector<std::vector<CellSize>>& sizes, const ContactSheetOptions& opt,
                            int columnGroups) {
  SheetLayout L;
  const int rows = int(sizes.size());
  int cols = 0;
  for (const auto& r : sizes) cols = std::max(cols, int(r.size()));
  std::vector<int> colW(size_t(cols), 0), rowH(size_t(rows), 0), rowTitle(size_t(rows), 0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < int(sizes[size_t(r)].size()); ++c) {
      const CellSize& s = sizes[size_t(r)][size_t(c)];
      if (!s.used) continue;
      colW[size_t(c)] = std::max({colW[size_t(c)], s.w, s.titleW});
      rowH[size_t(r)] = std::max(rowH[size_t(r)], s.h);
      if (s.titleW > 0) rowTitle[size_t(r)] = lineHeight(titleFont(opt)) + opt.titleGap;
    }
  std::vector<int> colX(size_t(cols), 0), rowY(size_t(rows), 0);
  int x = opt.margin;
  for (int c = 0; c < cols; ++c) {
    colX[size_t(c)] = x;
    x += colW[size_t(c)];
    if (c + 1 < cols) x += (columnGroups > 1 && (c + 1) % columnGroups == 0) ? opt.groupGap : opt.gap;
  }
  L.width = x + opt.margin;
  int y = opt.margin;
  L.headingX = opt.margin;
  L.headingY = opt.margin;
  if (!opt.heading.empty()) {
    y += lineHeight(headingFont(opt)) + 2 * opt.gap;
    L.width = std::max(L.width, 2 * opt.margin + textWidth(opt.heading, headingFont(opt)));
  }
  for (int r = 0; r < rows; ++r) {
    rowY[size_t(r)] = y;
    y += rowTitle[size_t(r)] + rowH[size_t(r)];
    if (r + 1 < rows) y += opt.gap;
  }
  L.height = y + opt.margin;
  L.cells.resize(size_t(rows));
  for (int r = 0; r < rows; ++r) {
    L.cells[size_t(r)].resize(sizes[size_t(r)].size());
    for (int c = 0; c < int(sizes[size_t(r)].size()); ++c) {
      const CellSize& s = sizes[size_t(r)][size_t(c)];
      CellRect& cr = L.cells[size_t(r)][size_t(c)];
      if (!s.used) continue;
      cr.used = true;
      cr.width = s.w;
      cr.height = s.h;
      cr.x = colX[size_t(c)] + (colW[size_t(c)] - s.w) / 2;
      cr.y = rowY[size_t(r)] + rowTitle[size_t(r)];
      cr.titleX = colX[size_t(c)] + (colW[size_t(c)] - s.titleW) / 2;
      cr.titleY = rowY[size_t(r)];
    }
  }
  return L;
}

std::vector<std::vector<CellSize>> cellSizes(const SheetGrid& grid, const ContactSheetOptions& opt) {
  std::vector<std::vector<CellSize>> sizes(grid.size());
  for (size_t r = 0; r < grid.size(); ++r) {
    sizes[r].resize(grid[r].size());
    for (size_t c = 0; c < grid[r].size(); ++c) {
      if (!grid[r][c]) continue;
      CellSize& s = sizes[r][c];
      s.used = true;
      displaySize(grid[r][c]->image, opt, s.w, s.h);
      s.titleW = textWidth(grid[r][c]->title, titleFont(opt));
    }
  }
  return sizes;
}

}  // namespace

SheetLayout layoutContactSheet(const SheetGrid& grid, const ContactSheetOptions& opt, int columnGroups) {
  return layoutFromSizes(cellSizes(grid, opt), opt, columnGroups);
}

Image composeContactSheet(const SheetGrid& grid, const ContactSheetOptions& opt, int columnGroups,
                          SheetLayout* layoutOut) {
  const SheetLayout L = layoutContactSheet(grid, opt, columnGroups);
  Image sheet(L.width, L.height, {"R", "G", "B"});
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x)
      for (int c = 0; c < 3; ++c) sheet.at(x, y, c) = opt.background[c];
  if (!opt.heading.empty())
    draw::drawText(sheet, L.headingX, L.headingY, opt.heading, headingFont(opt), opt.textColor);
  for (size_t r = 0; r < grid.size(); ++r)
    for (size_t c = 0; c < grid[r].size(); ++c) {
      if (!grid[r][c]) continue;
      const CellRect& cr = L.cells[r][c];
      Image img = colorImage(grid[r][c]->image, grid[r][c]->title.empty() ? "contact sheet cell" : grid[r][c]->title);
      if (img.width != cr.width || img.height != cr.height) img = resampleArea(img, cr.width, cr.height);
      for (int y = 0; y < cr.height; ++y)
        for (int x = 0; x < cr.width; ++x)
          for (int k = 0; k < 3; ++k) sheet.at(cr.x + x, cr.y + y, k) = img.at(x, y, k);
      if (!grid[r][c]->title.empty())
        draw::drawText(sheet, cr.titleX, cr.titleY, grid[r][c]->title, titleFont(opt), opt.textColor);
    }
  if (layoutOut) *layoutOut = L;
  return sheet;
}

SheetGrid fig11Grid(const Fig11Views& v, const std::string& errorTitle) {
  SheetGrid grid(3, std::vector<std::optional<SheetCell>>(6));
  auto put = [&](const std::optional<ViewPair>& p, int row, int group) {
    if (!p) return;
    grid[size_t(row)][size_t(2 * group)] = SheetCell{p->label + "  reference", p->reference};
    grid[size_t(row)][size_t(2 * group + 1)] = SheetCell{p->label + "  reconstruction", p->reconstruction};
  };
  put(v.top, 0, 1);
  put(v.left, 1, 0);
  put(v.centre, 1, 1);
  put(v.right, 1, 2);
  put(v.bottom, 2, 1);
  // The error maps, left to right as the display turns: left, top, centre, bottom, right.
  std::vector<std::optional<SheetCell>> maps(6);
  bool any = false;
  int column = 0;
  for (const std::optional<ViewPair>* p : {&v.left, &v.top, &v.centre, &v.bottom, &v.right}) {
    if (*p && (*p)->errorMap) maps[size_t(column)] = SheetCell{(*p)->label + "  " + errorTitle, *(*p)->errorMap}, any = true;
    ++column;
  }
  if (any) grid.push_back(maps);
  return grid;
}

Image composeFig11Sheet(const Fig11Views& views, const ContactSheetOptions& opt, SheetLayout* layoutOut,
                        const std::string& errorTitle) {
  return composeContactSheet(fig11Grid(views, errorTitle), opt, 2, layoutOut);
}

Image errorMapImage(const std::vector<float>& error, int width, int height, double maxValue,
                    const std::vector<uint8_t>* mask) {
  Image img(width, height, {"R", "G", "B"});
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
    const bool on = !mask || (*mask)[i] != 0;
    const float e = error[i];
    const Vec3 c = on && std::isfinite(e) ? colorMap(ColorMap::Viridis, std::clamp(double(e) / maxValue, 0.0, 1.0))
                                          : Vec3(0.5f);
    for (int k = 0; k < 3; ++k) img.data[i * 3 + size_t(k)] = c[k];
  }
  return img;
}

Image toDisplay(const Image& linear, const std::string& space, float exposure) {
  Image out = colorImage(linear, "image");
  for (float& v : out.data) v *= exposure;
  ColorSystem::instance().convertImage(out, space, "srgb");
  for (float& v : out.data) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  return out;
}

Image resampleArea(const Image& img, int width, int height) {
  Image out(std::max(width, 0), std::max(height, 0), img.channels);
  if (out.width == 0 || out.height == 0 || img.width == 0 || img.height == 0) return out;
  // Per output index: the source pixels it covers and their weights (overlap / footprint).
  struct Tap {
    int i;
    double w;
  };
  auto taps = [](int src, int dst) {
    std::vector<std::vector<Tap>> t(static_cast<size_t>(dst));
    const double s = double(src) / dst;
    for (int o = 0; o < dst; ++o) {
      const double a = o * s, b = (o + 1) * s;
      double total = 0.0;
      for (int i = int(std::floor(a)); i < std::min(src, int(std::ceil(b))); ++i) {
        const double w = std::min(b, double(i + 1)) - std::max(a, double(i));
        if (w > 0.0) t[size_t(o)].push_back({i, w}), total += w;
      }
      for (Tap& tp : t[size_t(o)]) tp.w /= total;
    }
    return t;
  };
  const auto tx = taps(img.width, out.width), ty = taps(img.height, out.height);
  const int nc = img.numChannels();
  parallelForRange(
      out.height,
      [&](int64_t y0, int64_t y1) {
        std::vector<double> acc(static_cast<size_t>(nc));
        for (int64_t y = y0; y < y1; ++y)
          for (int x = 0; x < out.width; ++x) {
            std::fill(acc.begin(), acc.end(), 0.0);
            for (const Tap& a : ty[size_t(y)])
              for (const Tap& b : tx[size_t(x)])
                for (int c = 0; c < nc; ++c) acc[size_t(c)] += a.w * b.w * img.at(b.i, a.i, c);
            for (int c = 0; c < nc; ++c) out.at(x, int(y), c) = float(acc[size_t(c)]);
          }
      },
      nullptr, 4);
  return out;
}

}  // namespace inim
