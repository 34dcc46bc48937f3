// The panel estimators behind their one interface: the factory returns each estimator, and
// each gives the same image bit for bit on one and on two threads (its per-tile caches filled
// in a fixed order).
#include <gtest/gtest.h>

#include "display_view/estimators/panel_estimator.h"
#include "display_view/view_renderer.h"
#include "real_setup.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

const PanelEstimator kEstimators[] = {PanelEstimator::PointSample, PanelEstimator::Footprint,
                                      PanelEstimator::Quadrature};

}  // namespace

TEST(PanelEstimators, FactoryReturnsEachEstimator) {
  RealSetup r;
  ViewSettings s;
  s.progress = false;
  const EstimatorContext context(*r.camera, defaultCamera().sensor, *r.mla, *r.panel, r.layout.activeArea(), s);
  for (PanelEstimator e : kEstimators) {
    const auto estimator = makePanelEstimator(e, context);
    ASSERT_NE(estimator, nullptr) << panelEstimatorName(e);
    EXPECT_EQ(estimator->kind(), e);
    PanelEstimator parsed;
    ASSERT_TRUE(parsePanelEstimator(panelEstimatorName(e), parsed));
    EXPECT_EQ(parsed, e);
    // A tile estimator sees the display at the image centre.
    const Vec3d rgb = estimator->beginTile()->pixel(r.camera->width() / 2, r.camera->height() / 2);
    EXPECT_GT(rgb.x + rgb.y + rgb.z, 0.0) << panelEstimatorName(e);
  }
  PanelEstimator unchanged = PanelEstimator::Footprint;
  EXPECT_FALSE(parsePanelEstimator("aperture", unchanged));  // retired
  EXPECT_EQ(unchanged, PanelEstimator::Footprint);
}

TEST(PanelEstimators, BitIdenticalOnOneAndTwoThreads) {
  const RealSetup r;
  for (PanelEstimator e : kEstimators) {
    SCOPED_TRACE(panelEstimatorName(e));
    expectBitIdenticalOnOneAndTwoThreads(r, e, e == PanelEstimator::Quadrature ? 2 : 3, 9);
  }
}
