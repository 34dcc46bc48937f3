#pragma once
// The panel's cover glass as the studies see it (braiding, flip-onset, telecentric, image-plane;
// not part of the public interface). The view simulation's PanelEmitter refracts every ray
// through a plate of thickness t and index n on the emitting plane (z from -g to -g + t); seen
// through it, the panel sits t (1 - 1/n) nearer the lenslets, at the optical gap
// g_eff = g - t (1 - 1/n) (paraxial), which the pinhole synthesis (rays in air at g) does not see.
#include <memory>
#include <string>

#include "core/image.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "spectral/dispersion.h"
#include "view/panel_emitter.h"

namespace inim::study_detail {

struct CoverGlassOptics {
  bool present = false;
  double thicknessMm = 0.0;
  double n = 1.0;  // at the wavelength asked for
  std::string material;
  // The optical gap of a panel at physical gap g seen through the glass (g itself without glass).
  double opticalGap(double g) const { return g - thicknessMm * (1.0 - 1.0 / n); }
};

inline CoverGlassOptics coverGlassOptics(const Display& d, float lambdaNm) {
  CoverGlassOptics c;
  if (!d.panel.coverGlass.has_value() || !(d.panel.coverGlass->thicknessMm > 0.0)) return c;
  c.present = true;
  c.thicknessMm = d.panel.coverGlass->thicknessMm;
  c.material = d.panel.coverGlass->material;
  c.n = double(MaterialCatalog::standard().dielectric(c.material)->n(lambdaNm));
  return c;
}

// A PanelEmitter used for its geometry only: where a ray that reached the emitting plane meets
// the emitter (PanelEmitter::emissionPointPx: refracted through the cover glass when `glass` is
// on and the panel has one), and the factor it applies. Its drive image is black.
inline std::unique_ptr<PanelEmitter> geometryEmitter(const Display& d, const EiLayout& L, double g, bool glass) {
  EmitterSettings es;
  es.coverGlass = glass;
  return std::make_unique<PanelEmitter>(d.panel, L, Image(L.eiaW, L.eiaH, {"R", "G", "B"}), "(geometry only)", g, es);
}

}  // namespace inim::study_detail
