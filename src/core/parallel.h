#pragma once
// Parallel loops over tiles and ranges on TBB. The work for an index never depends on
// which thread runs it, so results are bit-identical for any thread count. Interrupted (core/interrupt.h) stops them.
#include <cstdint>
#include <functional>
#include <memory>

namespace inim {

class ProgressBar;

// Limits TBB to `threads` worker threads while alive (0 = all cores).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();

 private:
  std::shared_ptr<void> control_;
};

struct Tile {
  int x0, y0, x1, y1;  // pixel bounds, [x0, x1) x [y0, y1)
};

// Calls fn(tile) for every tile of a width x height image; reports pixels to `progress`.
void parallelForTiles(int width, int height, const std::function<void(const Tile&)>& fn,
                      ProgressBar* progress = nullptr, int tileSize = 32);

// Calls fn(begin, end) on chunks of [0, count) of at most `grain`, the same chunks in every run
// and at any thread count (callers may batch by chunk).
void parallelForRange(int64_t count, const std::function<void(int64_t, int64_t)>& fn,
                      ProgressBar* progress = nullptr, int64_t grain = 1024);

int hardwareThreads();

// Gives the calling thread the lowest scheduling priority (nice 19), for background work that
// should only use what the rest of the program leaves; a no-op where that is not allowed.
void lowerThisThreadsPriority();

}  // namespace inim
