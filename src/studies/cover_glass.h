#pragma once
// The panel's cover glass as the studies use it (not part of the public interface): its optics
// (display/cover_glass.h) and an emitter that refracts through it.
#include <memory>

#include "core/image.h"
#include "display/cover_glass.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "display_view/panel_emitter.h"

namespace inim::study_detail {

// A PanelEmitter used for its geometry only: where a ray that reached the emitting plane meets
// the emitter (PanelEmitter::emissionPointPx: refracted through the cover glass when `glass` is
// on and the panel has one), and the factor it applies. Its drive image is black.
inline std::unique_ptr<PanelEmitter> geometryEmitter(const Display& d, const EiLayout& L, double g, bool glass) {
  EmitterSettings es;
  es.coverGlass = glass;
  return std::make_unique<PanelEmitter>(d.panel, L, Image(L.eiaW, L.eiaH, {"R", "G", "B"}), "(geometry only)", g, es);
}

}  // namespace inim::study_detail
