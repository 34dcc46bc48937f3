#pragma once
// Where a splat scene sits in the display frame by default. A splat file is in COLMAP/OpenCV
// axes (x right, y down, z forward, away from the capturing camera) and has no units; the
// display frame (docs/design.md §2.2) has x right, y up, z toward the viewer, in mm. So:
//  - rotate 180 deg about x: (x, y, z) -> (x, -y, -z), which keeps x and turns the scene to
//    face the viewer as the training cameras saw it;
//  - take the robust box of the splat positions, the 2nd to 98th percentile per axis (stray
//    background splats and floaters far out do not set the size), and scale it uniformly so
//    its x and y extents fill `fill` of the panel (the default display's 151.8 x 65 mm);
//  - translate the box centre to the origin, on the MLA plane, so the scene straddles it.
//
//   SplatFrame f = defaultSplatFrame(g);         // splat -> display mm
//   Point3 p = f.toField(g.position[0]);
#include "splats/gaussians.h"
#include "splats/splat_field.h"

namespace inim {

// The frame of the default display's panel (optics/displays/paper-prototype.json), mm, as
// scenes/paper-fig7.json is framed: loadField does not know the display a field will be shown on.
constexpr float kSplatPanelWidthMm = 151.8f, kSplatPanelHeightMm = 65.0f;

struct SplatBox {
  Vec3 lo, hi;
};
// Per-axis `lowPct`..`highPct` percentiles of the positions (splat frame).
SplatBox robustSplatBox(const Gaussians& g, float lowPct = 2.0f, float highPct = 98.0f);

SplatFrame defaultSplatFrame(const Gaussians& g, float widthMm = kSplatPanelWidthMm,
                             float heightMm = kSplatPanelHeightMm, float fill = 0.9f);

}  // namespace inim
