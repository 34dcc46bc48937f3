#pragma once
// An integral-imaging display: a panel, an MLA, the gaps and the elemental-image (EI) layout,
// read from optics/displays/*.json (format: optics/README.md).
#include <optional>
#include <string>
#include <vector>

#include "display/mla.h"
#include "display/optical_stack.h"
#include "display/panel.h"

namespace inim {

// How EIs sit relative to the lenslets used for ray generation (optics/README.md):
//  Parallel: the paper's. Pinholes at the EI centres, on the EI grid (pitch = EI px * pixel);
//            every EI's central ray is parallel to z. The physical lens pitch is not used
//            for generation (the paper's code placed its pinholes at 0.9875 mm, not 1.0 mm).
//  ToedIn:   pinholes at the physical lens centres (pitch P); each EI centred on the
//            projection of its lenslet centre from the viewpoint (0, 0, D), so the EI pitch is
//            P (1 + g / D); EI positions are rounded to whole pixels, EIs keep ei_px pixels.
//  LensGrid: pinholes at the physical lens centres (pitch P), EIs contiguous on the EI grid
//            (pitch EI px * pixel): the chief rays the physical display really emits when it
//            shows an EIA made for the parallel layout.
enum class EiLayoutKind { Parallel, ToedIn, LensGrid };
const char* layoutName(EiLayoutKind k);

struct Display {
  std::string name;
  std::string file;
  Panel panel;
  Mla mla;
  double generationGapMm = 0.0;      // panel to pinhole plane for ray generation (g = f)
  double reconstructionGapMm = 0.0;  // panel to MLA reference plane when viewing
  int eiWidthPx = 0, eiHeightPx = 0;
  int eiCols = 0, eiRows = 0;        // EI count: columns (x) and rows (y)
  EiLayoutKind layout = EiLayoutKind::Parallel;
  std::optional<double> viewingDistanceMm;  // required for toed-in; analysis otherwise
  std::vector<std::string> assumptions;
  // The optical stack the file gives in place of "mla" (docs/formats.md §3.6a). When it is one
  // lens array behind air, `mla` and reconstructionGapMm are derived from it and every stage
  // uses them. Otherwise (`stackTraced`), `mla` is the equivalent MLA that places the EIs
  // (equivalentMla), the gap is the panel's to the stack's principal plane H, and `view`
  // refracts through every layer.
  std::optional<OpticalStack> stack;
  bool stackTraced = false;
};

// Reads a display description. "panel" and "mla" are either inline objects, a file path
// ending in .json (relative to the display file), or a catalog name resolved to
// optics/panels/<name>.json or optics/mlas/<name>.json under the data folder.
// Validates the layout too (computeLayout), so a display that loads can generate rays.
Display loadDisplay(const std::string& path);
// optics/displays/paper-prototype.json.
std::string defaultDisplayPath();
// `path`, or the default display when it is empty.
std::string displayPathOrDefault(const std::string& path);

}  // namespace inim
