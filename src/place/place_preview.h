#pragma once
// The placement page's previews (docs/place-api.md, "The previews"):
//   level 0  one query ray per lenslet, the lenslet's central ray reversed from the VCP as the
//            EIA's queries are (synthesis/orthoscopic.h): the paper's Fig. 4 preview;
//   level 1  the same projection with n x n query rays per lenslet, spread over its cell;
//   level 2  a pinhole camera at the viewing distance on the display's axis: the scene where it
//            stands in space, with the display area outlined (no VCP clipping, as a reference).
// Every pixel is the first hit's colour, painted pure red (255, 0, 0) where the hit lies within
// the tolerance of the MLA plane (no other pixel is ever that exact red); at levels 0 and 1 the
// parts behind the MLA (virtual images) are shown cooler and darker than those in front; no hit
// is dark grey. Level 0 keeps up with a drag: it asks Field::queryPreview and, for spectral
// fields, one wavelength sample per ray (levels 1 and 2 refine with the full query).
//
// Rendering runs in batches of rows; `cancelled` is asked between batches and a true answer
// ends the render with PreviewCancelled, so a newer placement interrupts an older one at once.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/transform.h"
#include "display/ei_layout.h"
#include "field/field.h"
#include "synthesis/preview.h"  // PreviewCancelled

namespace inim {

struct PreviewCounts {
  int real = 0, virtualHits = 0, onPlane = 0, missed = 0;
};

struct PreviewFrame {
  Image image;  // R, G, B, display-encoded (sRGB) in [0, 1]
  PreviewCounts counts;
  double exposure = 1.0;  // the linear factor used (auto on the first frame, then kept)
  // Level 0: what each lenslet's central ray met (its first sample), lenslet (k, l) at
  // l * eiCols + k, for the diagram of the same placement (PreviewSettings::knownHits).
  std::vector<LensletFirstHit> lensletHits;
};

struct PreviewRequest {
  int level = 0;
  int raysPerSide = 4;           // level 1: n x n rays per lenslet
  int cameraWidth = 480;         // level 2: image width (the height follows the display's aspect)
  int cameraSpp = 4;             // level 2: samples per pixel
  int wavelengthSamples = 2;     // spectral fields: samples per ray at level 1 (level 0: one)
  double viewingDistanceMm = 350.0;
  double onPlaneToleranceMm = 0.5;
  std::optional<double> exposure;  // absent: auto (99th percentile of the hits -> 0.9)
  uint64_t seed = 1;
};

PreviewFrame renderPlacePreview(const EiLayout& layout, const Field& field, const Transform& fieldToDisplay,
                                double vcpMm, const PreviewRequest& r,
                                const std::function<bool()>& cancelled = {});

// PNG bytes of a display-encoded RGB image (8 bits per channel).
std::string encodePng(const Image& rgb);

}  // namespace inim
