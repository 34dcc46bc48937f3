#include "display_view/view_settings.h"

#include "display_view/estimators/panel_estimator.h"

namespace inim {

const char* spectralSamplingName(SpectralSampling s) {
  return s == SpectralSampling::Primaries ? "primaries" : "visible";
}

const char* panelEstimatorName(PanelEstimator e) { return panelEstimators()[size_t(e)].name; }

bool parsePanelEstimator(const std::string& name, PanelEstimator& out) {
  for (const PanelEstimatorInfo& e : panelEstimators())
    if (name == e.name) {
      out = e.kind;
      return true;
    }
  return false;
}

}  // namespace inim
