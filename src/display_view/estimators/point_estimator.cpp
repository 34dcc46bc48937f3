#include "display_view/estimators/point_estimator.h"

#include "display_view/estimators/sample_tracer.h"
#include "display_view/view_renderer.h"

namespace inim {

namespace {

class PointTile final : public TileEstimator {
 public:
  explicit PointTile(const EstimatorContext& context) : context_(context), tracer_(context, counts_) {}
  Vec3d pixel(int x, int y) override {
    Vec3d rgb(0.0);
    tracer_.beginPixel(x, y);
    for (int i = 0; i < context_.settings.spp; ++i) tracer_.addSample(i, PanelRead{}, rgb);
    return rgb;
  }
  void addStats(ViewStats& stats) const override { stats.addRayCounts(counts_); }

 private:
  const EstimatorContext& context_;
  RayCounts counts_;
  SampleTracer tracer_;
};

}  // namespace

std::unique_ptr<TileEstimator> PointEstimator::beginTile() const { return std::make_unique<PointTile>(context_); }

}  // namespace inim
