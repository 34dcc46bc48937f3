#include "display_view/display_model.h"

#include <cmath>

#include "core/error.h"
#include "display/mla.h"
#include "mla_optics/ideal_mla.h"
#include "mla_optics/real_mla.h"
#include "mla_optics/stack_mla.h"

namespace inim {

const char* mlaKindName(MlaKind k) { return k == MlaKind::Real ? "real" : "ideal"; }

DisplayModel makeDisplayModel(const Display& d, const EiLayout& L, const Image& eia, const std::string& eiaFile,
                              MlaKind mla, double gapMm, const EmitterSettings& emitter) {
  DisplayModel m;
  m.gapMm = gapMm > 0.0 ? gapMm : d.reconstructionGapMm;
  if (!(m.gapMm > 0.0) || !std::isfinite(m.gapMm))
    throw InputError(d.file, "reconstruction_gap_mm", std::to_string(m.gapMm), "a gap > 0 mm");
  m.panel = std::make_unique<PanelEmitter>(d.panel, L, eia, eiaFile, m.gapMm, emitter);
  if (mla == MlaKind::Ideal && d.stack && d.stack->curved())
    m.mla = std::make_unique<CurvedIdealMla>(d, L, lensletFocus(d.mla).focalLengthMm, m.gapMm);
  else if (mla == MlaKind::Ideal)
    m.mla = std::make_unique<IdealLensletMla>(L, d.mla.pitchMm, lensletFocus(d.mla).focalLengthMm, m.gapMm);
  else if (d.stackTraced)
    m.mla = std::make_unique<StackMla>(d, L, m.gapMm);
  else
    m.mla = makeRealMla(d, L, m.gapMm);
  m.area = L.activeArea();
  return m;
}

}  // namespace inim
