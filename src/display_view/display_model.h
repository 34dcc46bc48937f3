#pragma once
// Everything the view simulation needs on the display side, built in one call (for `inim view`,
// `inim fig11` and benchmarks):
//
//   Display d = loadDisplay(path);
//   EiLayout L = computeLayout(d);
//   DisplayModel dm = makeDisplayModel(d, L, readImage("eia.exr"), "eia.exr", MlaKind::Real);
//   ViewResult r = renderView(*camera, sensor, *dm.mla, *dm.panel, dm.area, settings);
#include <memory>
#include <string>

#include "core/image.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/mla_model.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_renderer.h"

namespace inim {

enum class MlaKind { Real, Ideal };  // RealMla (mla stage) or IdealLensletMla (thin lenses)
const char* mlaKindName(MlaKind k);   // "real", "ideal"

struct DisplayModel {
  double gapMm = 0.0;                   // panel (z = -g) to the MLA reference plane
  std::unique_ptr<PanelEmitter> panel;  // the EIA on the panel's subpixels
  std::unique_ptr<MlaModel> mla;
  AreaMm area;                          // the lenslet array (EiLayout::activeArea): "on the display"
};

// `gapMm` <= 0: the display's reconstruction gap. The ideal MLA takes the lenslets' paraxial
// focal length (lensletFocus). InputError for a bad EIA (panel_emitter.h) or gap.
DisplayModel makeDisplayModel(const Display& d, const EiLayout& L, const Image& eia, const std::string& eiaFile,
                              MlaKind mla, double gapMm = 0.0, const EmitterSettings& emitter = {});

}  // namespace inim
