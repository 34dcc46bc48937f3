#pragma once
// Contact sheets: labelled images composed into one grid image (written as PNG).
//
// A sheet is a grid of cells. Each cell holds an image with its title above it. Columns are
// as wide as their widest image (or title), rows as tall as their tallest image; an image
// smaller than its cell is centred horizontally and aligned to the top. Empty cells are left
// blank. Cell images are taken as display values in [0, 1] (what a PNG stores, e.g. sRGB);
// use toDisplay() for linear images. Their colour is read as in metrics.h (R,G,B by name,
// else the first non-alpha channels, grey repeated); alpha is ignored.
//
// composeFig11Sheet() lays out the paper's Fig. 11: a cross of five viewing directions
// (centre, left, right, top, bottom), each a pair of cells "reference | reconstruction".
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/image.h"

namespace inim {

struct SheetCell {
  std::string title;  // drawn above the image (UTF-8)
  Image image;        // display values in [0, 1]
};

struct ContactSheetOptions {
  int margin = 12;             // around the whole sheet, px
  int gap = 16;                // between cells, px
  int groupGap = 40;           // between groups (the pairs of a Fig. 11 sheet), px
  double titleSize = 15.0;     // font size of cell titles, px (DejaVu Sans, see draw/text.h)
  int titleGap = 4;            // between a title and its image, px
  double headingSize = 20.0;   // font size of the sheet heading, px
  std::string heading;         // optional line of text at the top of the sheet
  int maxImageWidth = 0;       // > 0: larger images are downscaled (area average) to this width
  Vec3 background{1.0f, 1.0f, 1.0f};
  Vec3 textColor{0.0f, 0.0f, 0.0f};
};

// Where things went, in sheet pixels.
struct CellRect {
  int x = 0, y = 0, width = 0, height = 0;  // the image (after any downscaling)
  int titleX = 0, titleY = 0;                // top-left of the title text
  bool used = false;
};
struct SheetLayout {
  int width = 0, height = 0;
  int headingX = 0, headingY = 0;
  std::vector<std::vector<CellRect>> cells;  // [row][column]
};

// A grid of optional cells, rows of columns; rows may have different lengths.
// `columnGroups` > 1 adds options.groupGap (instead of gap) after every columnGroups-th
// column (the pairs of a Fig. 11 sheet use 2).
using SheetGrid = std::vector<std::vector<std::optional<SheetCell>>>;
SheetLayout layoutContactSheet(const SheetGrid& grid, const ContactSheetOptions& opt = {}, int columnGroups = 1);
Image composeContactSheet(const SheetGrid& grid, const ContactSheetOptions& opt = {}, int columnGroups = 1,
                          SheetLayout* layoutOut = nullptr);

// One viewing direction of a Fig. 11 sheet.
struct ViewPair {
  std::string label;  // e.g. "0°", "-7° H", "+7° V"
  Image reference;
  Image reconstruction;
  std::optional<Image> errorMap;  // e.g. CIEDE2000 per pixel as a colour map (errorMapImage)
};
struct Fig11Views {
  std::optional<ViewPair> centre, left, right, top, bottom;
};
// The cross: a 3 x 6 grid of cells,
//   row 0: [ -, - | top ref, top rec | -, - ]
//   row 1: [ left ref, left rec | centre ref, centre rec | right ref, right rec ]
//   row 2: [ -, - | bottom ref, bottom rec | -, - ]
// titled "<label>  reference" and "<label>  reconstruction"; when the pairs carry error maps, a
// fourth row holds them: [ left | top | centre | bottom | right ], titled "<label>  <errorTitle>".
SheetGrid fig11Grid(const Fig11Views& views, const std::string& errorTitle = "error");
// A per-pixel error (row-major, width x height) as a Viridis image, 0 at `maxValue` and above
// yellow; pixels where `mask` (optional, same size) is off are mid grey.
Image errorMapImage(const std::vector<float>& error, int width, int height, double maxValue,
                    const std::vector<uint8_t>* mask = nullptr);
Image composeFig11Sheet(const Fig11Views& views, const ContactSheetOptions& opt = {}, SheetLayout* layoutOut = nullptr,
                        const std::string& errorTitle = "error");

// A linear image in colour space `space` as sRGB-encoded display values (3 channels, R G B),
// after multiplying by `exposure`, through OpenColorIO; values are clamped to [0, 1].
Image toDisplay(const Image& linear, const std::string& space = "lin_rec709", float exposure = 1.0f);
// Area-average downscale (box filter with fractional pixel coverage) to the given size.
Image resampleArea(const Image& img, int width, int height);

}  // namespace inim
