#include "core/parallel.h"

#include <sys/resource.h>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "core/interrupt.h"
#include "core/progress.h"

namespace inim {

ThreadLimit::ThreadLimit(int threads) {
  if (threads > 0)
    control_ = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     size_t(threads));
}
ThreadLimit::~ThreadLimit() = default;

int hardwareThreads() { return tbb::info::default_concurrency(); }

void parallelForTiles(int width, int height, const std::function<void(const Tile&)>& fn,
                      ProgressBar* progress, int tileSize) {
  int nx = (width + tileSize - 1) / tileSize, ny = (height + tileSize - 1) / tileSize;
  tbb::parallel_for(tbb::blocked_range<int>(0, nx * ny, 1), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      throwIfInterrupted();  // cancels the loop; TBB rethrows in the caller
      int tx = t % nx, ty = t / nx;
      Tile tile{tx * tileSize, ty * tileSize, std::min(width, (tx + 1) * tileSize),
                std::min(height, (ty + 1) * tileSize)};
      fn(tile);
      if (progress) progress->add(uint64_t(tile.x1 - tile.x0) * uint64_t(tile.y1 - tile.y0));
    }
  });
}

// The simple partitioner splits [0, count) by halving down to `grain`, so the chunks are the same
// in every run and at any thread count. Callers form batches from their chunk (the EIA's field
// queries, Embree's ray streams), and a batch's makeup can change an answer at the edge of a
// triangle (the auto partitioner's chunks differed between runs in 6-13 EIA pixels of 6.2 M).
void parallelForRange(int64_t count, const std::function<void(int64_t, int64_t)>& fn,
                      ProgressBar* progress, int64_t grain) {
  tbb::parallel_for(
      tbb::blocked_range<int64_t>(0, count, size_t(grain)),
      [&](const tbb::blocked_range<int64_t>& r) {
        throwIfInterrupted();
        fn(r.begin(), r.end());
        if (progress) progress->add(uint64_t(r.end() - r.begin()));
      },
      tbb::simple_partitioner());
}

void lowerThisThreadsPriority() {
  // On Linux a nice value belongs to the thread (its id from gettid), not to the process.
  (void)setpriority(PRIO_PROCESS, id_t(gettid()), 19);
}

}  // namespace inim
