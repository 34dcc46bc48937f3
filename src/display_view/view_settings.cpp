#include "display_view/view_settings.h"

namespace inim {

const char* spectralSamplingName(SpectralSampling s) {
  return s == SpectralSampling::Primaries ? "primaries" : "visible";
}

const char* panelEstimatorName(PanelEstimator e) {
  switch (e) {
    case PanelEstimator::PointSample: return "point";
    case PanelEstimator::Footprint: return "footprint";
    case PanelEstimator::Quadrature: return "quadrature";
  }
  return "?";
}

bool parsePanelEstimator(const std::string& name, PanelEstimator& out) {
  for (PanelEstimator e : {PanelEstimator::PointSample, PanelEstimator::Footprint, PanelEstimator::Quadrature})
    if (name == panelEstimatorName(e)) {
      out = e;
      return true;
    }
  return false;
}

}  // namespace inim
