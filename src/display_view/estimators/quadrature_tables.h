#pragma once
// The Quadrature estimator's per-block aperture tables and block cameras (aperture_table.h,
// block_camera.h), each built once, when a pixel of its block is first rendered. A
// QuadratureTableCache shares them between renders through one camera that differ only in the
// display (the error budget's rungs at one pose): a block's table
// depends on the camera and on the key below, not on the panel, the EIA or the MLA's optics.
//
//   auto cache = std::make_shared<QuadratureTableCache>(camera);
//   ViewSettings vs;  vs.tableCache = cache;   // every render of `camera` with vs
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <vector>

#include "camera/camera_model.h"
#include "display_view/estimators/aperture_table.h"
#include "display_view/estimators/block_camera.h"

namespace inim {

// Everything a block's table and camera depend on besides the camera itself.
struct QuadratureTableKey {
  int grid = 0, blockSize = 1, blocksX = 1, blocksY = 1;
  float lambdaNm = 0.0f, frontZ = 0.0f;
  std::vector<float> colourLambdas;
  auto tie() const { return std::tie(grid, blockSize, blocksX, blocksY, lambdaNm, frontZ, colourLambdas); }
  bool operator<(const QuadratureTableKey& o) const { return tie() < o.tie(); }
};

class QuadratureTables {
 public:
  QuadratureTables(const CameraModel& camera, QuadratureTableKey key);
  // The block's table and camera, built on first use (thread safe; the same whichever thread
  // builds it). Rays traced to build them are added to rays().
  void ensure(size_t block) const;
  const ApertureTable& table(size_t block) const { return tables_[block]; }
  const BlockCamera& camera(size_t block) const { return cameras_[block]; }
  uint64_t rays() const { return rays_; }

 private:
  const CameraModel& cameraModel_;
  QuadratureTableKey key_;
  std::unique_ptr<std::once_flag[]> built_;
  mutable std::vector<ApertureTable> tables_;
  mutable std::vector<BlockCamera> cameras_;
  mutable std::atomic<uint64_t> rays_{0};
};

class QuadratureTableCache {
 public:
  explicit QuadratureTableCache(const CameraModel& camera) : camera_(camera) {}
  // The tables for `key`, made on first request. std::logic_error for another camera.
  std::shared_ptr<const QuadratureTables> tables(const CameraModel& camera, const QuadratureTableKey& key);

 private:
  const CameraModel& camera_;
  std::mutex mutex_;
  std::map<QuadratureTableKey, std::shared_ptr<const QuadratureTables>> tables_;
};

}  // namespace inim
