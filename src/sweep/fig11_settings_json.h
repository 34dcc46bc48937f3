#pragma once
// A design point's fig11 settings as JSON: what a plan's "fig11" object may hold, written in
// full into each point.json (defaults filled in), and read back when the point runs.
//   width, spp, aperture_grid, reference_spp, eia_spp, angle, distance_mm, seed (numbers);
//   mla ("real" | "ideal"), chief_rays ("pinhole" | "traced"), calibration, budget_calibration
//   (paths); poses, budget_rungs (lists of names); budget, depth_error, reference_every_pixel
//   (true | false).
#include "core/json_config.h"
#include "runs/fig11.h"

namespace inim {

// The settings as JSON, every key present.
Json fig11SettingsJson(const Fig11Settings& s);
// The settings of `o` over `defaults`; unknown keys and values out of range are InputErrors
// naming o's file and key path.
Fig11Settings fig11SettingsFromJson(const JsonObject& o, const Fig11Settings& defaults = {});
// A plan's defaults: fig11's, but with the references rendered at every pixel, so that points
// which change the display share them (Fig11Settings::referenceEveryPixel).
Fig11Settings sweepFig11Defaults();

}  // namespace inim
