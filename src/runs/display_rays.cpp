#include "runs/display_rays.h"

#include "core/error.h"
#include "core/format.h"
#include "core/progress.h"
#include "core/settings_table.h"
#include "mla_optics/real_mla.h"
#include "mla_optics/stack_mla.h"

namespace inim {

const char* chiefRaysName(ChiefRays c) { return c == ChiefRays::Pinhole ? "pinhole" : "traced"; }

DisplayRayChoice resolveDisplayRays(const std::optional<std::string>& chiefRays, bool realLens,
                                    const std::optional<std::string>& realLensRay,
                                    const std::optional<double>& wavelengthNm) {
  DisplayRayChoice c;
  if (chiefRays) {
    if (*chiefRays != "pinhole" && *chiefRays != "traced")
      throw InputError("", "chief_rays", "\"" + *chiefRays + "\"",
                       "pinhole (the pinhole model's rays) or traced (each pixel's real chief ray through the stack)");
    c.chiefRays = *chiefRays == "pinhole" ? ChiefRays::Pinhole : ChiefRays::Traced;
    if (realLens)
      throw InputError("", "chief_rays", "\"" + *chiefRays + "\"",
                       "no --real-lens with it (--real-lens is the single-lens model's own rays)");
  }
  const bool traced = c.chiefRays == ChiefRays::Traced;
  if (wavelengthNm && traced) {
    checkSettingRange(*findSetting("wavelength_nm"), *wavelengthNm, "", "wavelength_nm");
    c.traced.wavelengthNm = *wavelengthNm;
  }
  c.realLens = resolveRealLens(realLens, realLensRay, traced ? std::nullopt : wavelengthNm);
  return c;
}

bool tracesChiefRays(const Display& d, const DisplayRayChoice& c) {
  if (c.chiefRays) return *c.chiefRays == ChiefRays::Traced;
  return d.stackTraced && !c.realLens;
}

DisplayRays displayRaysFor(const Display& d, const EiLayout& L, const DisplayRayChoice& c, bool progress) {
  DisplayRays r;
  const bool bar = progress && ProgressBar::stderrIsTerminal();
  if (c.realLens) {
    std::unique_ptr<RealMla> mla = RealMla::fromDisplay(d, L, L.gapMm);
    ProgressBar pb("real-lens rays", uint64_t(L.numRays()), bar);
    RealLensRayStats st;
    r.rays = generateRealLensRays(L, *mla, *c.realLens, &st, &pb);
    pb.finish();
    r.summary = summaryText(*c.realLens, st);
  } else if (tracesChiefRays(d, c) || (d.stack && d.stack->curved())) {
    // A curved stack's pinhole rays too: its lenslets' principal points are not on one plane.
    TracedChiefRayOptions o = c.traced;
    o.pinholeOnly = !tracesChiefRays(d, c);
    ProgressBar pb(o.pinholeOnly ? "pinhole rays" : "chief rays", uint64_t(L.numRays()), bar);
    TracedChiefRayStats st;
    // The stack as built: the generation gap is the pinhole model's.
    r.rays = generateTracedChiefRays(L, displayStackAtGap(d, d.reconstructionGapMm), d.reconstructionGapMm, o, &st, &pb);
    pb.finish();
    r.summary = o.pinholeOnly ? formatText("pinhole rays through the principal points of a curved array: %llu rays",
                                           (unsigned long long)st.rays)
                              : summaryText(o, st);
  }
  return r;
}

}  // namespace inim
