#pragma once
// Placement preview, like the paper's Fig. 4: where the scene sits relative to the MLA, the
// panel and the VCP, drawn from the central ray of every lenslet (the ray from the EI centre
// through its pinhole), as two orthographic projections side by side, both with z up (the
// viewer at the top):
//   left:  top view, x-z (x to the right), the rays of the middle EI row;
//   right: side view, y-z (y to the right), the rays of the middle EI column.
// Drawn: the scene's bounds through the placement (grey box), the panel plane z = -g (dark
// grey), the MLA plane z = 0 (black) highlighted in red where the scene crosses it, the VCP
// z = D_VCP (dashed blue), the central query rays from the VCP to their first hit (light
// blue), and the first hit of every lenslet's central ray: orange for real (z > 0, in front of
// the MLA), blue for virtual (z < 0), green on the MLA plane (|z| <= P / 2). Drawn with
// Cairo and Pango (src/draw).
#include <cstdint>
#include <functional>
#include <span>

#include "core/image.h"
#include "core/transform.h"
#include "display/ei_layout.h"
#include "field/field.h"

namespace inim {

// Thrown by a preview whose `cancelled` answered true (a newer placement superseded it).
struct PreviewCancelled {};

// Where one lenslet's central query ray first met the field (FieldSample's depth and opacity).
struct LensletFirstHit {
  float depth = kInfinity;
  float opacity = 0.0f;
};

struct PreviewSettings {
  int width = 1800;  // image width, px (the height follows the scene's depth extent)
  uint64_t seed = 1;
  // The central rays' answers when the caller has them already (the placement page's level-0
  // preview asks the same rays), lenslet (k, l) at l * eiCols + k; empty: the field is queried.
  std::span<const LensletFirstHit> knownHits;
  // Asked between the drawing's stages (the live placement page drops superseded work); none: never.
  std::function<bool()> cancelled;
};

struct PreviewResult {
  Image image;  // RGB in [0, 1], display-encoded (write as PNG)
  int lenslets = 0, real = 0, virtualHits = 0, onPlane = 0, missed = 0;
  int crossingLenslets = 0;  // lenslets where the scene crosses the MLA plane
};

PreviewResult renderPlacementPreview(const EiLayout& L, const Field& field, const Transform& fieldToDisplay,
                                     double vcpMm, const PreviewSettings& s = {});

}  // namespace inim
