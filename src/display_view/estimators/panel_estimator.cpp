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

std::unique_ptr<PixelEstimator> makePanelEstimator(PanelEstimator kind, const EstimatorContext& context) {
  switch (kind) {
    case PanelEstimator::PointSample: return std::make_unique<PointEstimator>(context);
    case PanelEstimator::Footprint: return std::make_unique<FootprintEstimator>(context);
    case PanelEstimator::Quadrature: return std::make_unique<QuadratureEstimator>(context);
  }
  return nullptr;
}

}  // namespace inim
