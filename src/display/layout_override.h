#pragma once
// Command-line / run-file overrides of a loaded display's EI layout (shared by `inim rays`,
// `inim eia` and `inim triads`), re-validated so that errors name the setting.
#include <optional>
#include <string>

#include "display/display.h"
#include "display/ei_layout.h"

namespace inim {

struct LayoutOverride {
  std::optional<std::string> layout;          // "parallel", "toed-in", "lens-grid"
  std::optional<double> viewingDistanceMm;    // D, required for toed-in (or from the display)
  std::string layoutKey = "layout";           // how messages name the settings
  std::string distanceKey = "viewing_distance_mm";
};

// Applies the override and returns the display's layout (computeLayout). InputError naming
// the setting for an unknown layout, D <= 0, a toed-in layout without D, or EIs that would
// overlap / not fit the panel at the given D.
EiLayout applyLayoutOverride(Display& d, const LayoutOverride& o);

EiLayoutKind parseLayoutKind(const std::string& s, const std::string& key = "layout");

}  // namespace inim
