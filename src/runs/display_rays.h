#pragma once
// The display rays an EIA is made along (docs/formats.md §3.6a): the pinhole model's
// (rays/pinhole_rays.h), the real-lens rays of today's single MLA (`--real-lens`,
// mla_optics/real_lens_rays.h), or the chief rays traced through the display's optical stack
// (`--chief-rays traced`, mla_optics/stack_chief_rays.h). Traced chief rays are the default for a
// display whose stack is not today's one thin layer; pinhole rays for the rest, as before.
#include <optional>
#include <string>

#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/real_lens_rays.h"
#include "mla_optics/stack_chief_rays.h"
#include "rays/ray_set.h"

namespace inim {

enum class ChiefRays { Pinhole, Traced };
const char* chiefRaysName(ChiefRays c);

struct DisplayRayChoice {
  std::optional<ChiefRays> chiefRays;          // absent: the display's default
  std::optional<RealLensRayOptions> realLens;  // `--real-lens` (needs chiefRays absent)
  TracedChiefRayOptions traced;                // with traced chief rays
};

// The choice as a run gives it (absent: not given). InputError naming chief_rays for an unknown
// value or for --real-lens with --chief-rays, naming wavelength_nm when it has no real rays to
// apply to; resolveRealLens's errors otherwise.
DisplayRayChoice resolveDisplayRays(const std::optional<std::string>& chiefRays, bool realLens,
                                    const std::optional<std::string>& realLensRay,
                                    const std::optional<double>& wavelengthNm);

// Whether the run traces chief rays through `d`'s stack.
bool tracesChiefRays(const Display& d, const DisplayRayChoice& c);

struct DisplayRays {
  std::optional<RaySet> rays;  // absent: the pinhole rays
  std::string summary;         // how they were made ("" for pinhole rays)
};

// The rays for layout `L` of display `d` (a progress bar on a terminal when `progress`).
DisplayRays displayRaysFor(const Display& d, const EiLayout& L, const DisplayRayChoice& c, bool progress);

}  // namespace inim
