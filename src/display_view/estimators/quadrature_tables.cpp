#include "display_view/estimators/quadrature_tables.h"

#include <algorithm>
#include <stdexcept>

namespace inim {

QuadratureTables::QuadratureTables(const CameraModel& camera, QuadratureTableKey key)
    : cameraModel_(camera), key_(std::move(key)) {
  const size_t n = size_t(key_.blocksX) * size_t(key_.blocksY);
  built_ = std::make_unique<std::once_flag[]>(n);
  tables_.resize(n);
  cameras_.resize(n);
}

void QuadratureTables::ensure(size_t b) const {
  std::call_once(built_[b], [&] {
    const int W = cameraModel_.width(), H = cameraModel_.height(), s = key_.blockSize;
    const int bx = int(b % size_t(key_.blocksX)), by = int(b / size_t(key_.blocksX));
    const Vec2 centre(0.5f * float(bx * s + std::min(W, (bx + 1) * s)), 0.5f * float(by * s + std::min(H, (by + 1) * s)));
    uint64_t rays = 0;
    tables_[b] = buildApertureTable(cameraModel_, centre, key_.lambdaNm, key_.grid, rays, key_.frontZ);
    if (tables_[b].valid())
      cameras_[b] = buildBlockCamera(cameraModel_, tables_[b], centre, key_.lambdaNm, key_.frontZ, key_.colourLambdas,
                                     rays);
    rays_ += rays;
  });
}

std::shared_ptr<const QuadratureTables> QuadratureTableCache::tables(const CameraModel& camera,
                                                                    const QuadratureTableKey& key) {
  if (&camera != &camera_) throw std::logic_error("QuadratureTableCache: used with another camera");
  std::lock_guard<std::mutex> lock(mutex_);
  auto& t = tables_[key];
  if (!t) t = std::make_shared<QuadratureTables>(camera, key);
  return t;
}

}  // namespace inim
