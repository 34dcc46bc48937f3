#include "display_view/estimators/panel_estimator.h"

#include "display_view/estimators/footprint_estimator.h"
#include "display_view/estimators/point_estimator.h"
#include "display_view/estimators/quadrature_estimator.h"

namespace inim {

namespace {

bool anythingDispersive(const CameraModel& camera, const MlaModel& mla, const PanelEmitter& panel,
                        const ViewSettings& settings) {
  return camera.isDispersive() || mla.isDispersive() || panel.isDispersive() || settings.perWavelengthRays;
}

}  // namespace

EstimatorContext::EstimatorContext(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                         const PanelEmitter& panel, const AreaMm& area, const ViewSettings& settings)
    : camera(camera),
      mla(mla),
      panel(panel),
      area(area),
      settings(settings),
      frontZ(mla.frontZ() + 0.01f),
      referenceLambdaNm(float(settings.referenceLambdaNm)),
      cameraDispersive(camera.isDispersive()),
      channels(sensor, panel, anythingDispersive(camera, mla, panel, settings), settings.spectral) {}

namespace {

template <class E>
std::unique_ptr<PixelEstimator> make(const EstimatorContext& context) {
  return std::make_unique<E>(context);
}

}  // namespace

const std::vector<PanelEstimatorInfo>& panelEstimators() {
  static const std::vector<PanelEstimatorInfo> table = {
      {PanelEstimator::PointSample, "point", "Monte Carlo: the panel's radiance where each camera ray lands",
       make<PointEstimator>},
      {PanelEstimator::Footprint, "footprint", "Monte Carlo: the panel averaged over each ray's footprint box",
       make<FootprintEstimator>},
      {PanelEstimator::Quadrature, "quadrature", "deterministic: the pixel and aperture integrated by tabled quadrature",
       make<QuadratureEstimator>},
  };
  return table;
}

std::unique_ptr<PixelEstimator> makePanelEstimator(PanelEstimator kind, const EstimatorContext& context) {
  return panelEstimators()[size_t(kind)].make(context);
}

}  // namespace inim
