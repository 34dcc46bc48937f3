#pragma once
// The placement page's model (docs/place-api.md), apart from HTTP: the field shown, the state
// the page controls, the previews rendered for it in one worker thread, and the write jobs.
//
// A change of state (putState) makes a new revision. The worker renders level 0 of the newest
// revision at once, then levels 1 and 2 once the state has been still for `quietMs`; a newer
// revision interrupts it at its next batch of rays (place_preview.h). A second thread, at the
// lowest priority, draws the diagram of the newest revision whose level 0 is done, once a
// request has asked for it, so the diagram never holds up a level 0. A request for an image
// waits until that image of its revision is ready, and is answered "stale" at once when the
// state has moved on, so the page never waits for old work; a level 0 or diagram already under
// way is finished and served.
//
//   PlaceSession session(options);              // InputError for a bad field, display or run file
//   Json st = session.putState(R"({"vcp_mm": 80})");  // InputError (400) changes nothing
//   ImageAnswer a = session.image(ImageKind::Level0, st["revision"], std::chrono::seconds(30));
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/json_config.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "field_files/field_factory.h"
#include "place/place_jobs.h"
#include "place/place_state.h"
#include "synthesis/preview.h"

namespace inim {

struct PlaceOptions {
  std::string fieldPath;    // "": the default scene
  std::string displayPath;  // "": the paper's prototype
  std::string runPath;      // a run file to start from (placement, display, VCP, layout), or ""
  std::string outDir = "out/place";
  int quietMs = 150;        // stillness before levels 1 and 2
  uint64_t seed = 1;
};

enum class ImageKind { Level0 = 0, Level1 = 1, Level2 = 2, Diagram = 3 };
constexpr int kImageKinds = 4;

struct ImageAnswer {
  enum class Status { Ready, Stale, Future, Timeout, Failed } status = Status::Ready;
  std::string png, error;
  Json counts;            // {"real", "virtual", "on_plane", "missed"}
  double serverMs = 0.0;  // the state change (PUT) to this image ready
  uint64_t revision = 0;
};

// The display as the state sets it: file, layout and viewing distance applied.
struct PlaceDisplay {
  Display display;
  EiLayout layout;
};

class PlaceSession {
 public:
  explicit PlaceSession(const PlaceOptions& options);
  // With a field already loaded (options.fieldPath then only names it).
  PlaceSession(const PlaceOptions& options, LoadedField field);
  ~PlaceSession();
  PlaceSession(const PlaceSession&) = delete;
  PlaceSession& operator=(const PlaceSession&) = delete;

  Json info() const;
  Json state() const;
  // Applies a JSON body of state keys; InputError (a 400) changes nothing.
  Json putState(const std::string& body);
  ImageAnswer image(ImageKind kind, uint64_t revision, std::chrono::milliseconds timeout);
  // Server-side times from the state change to each image ready: count, median, p95, max (ms).
  Json latency() const;

  PlaceJobs& jobs() { return *jobs_; }
  // A snapshot of what a job needs: the state and the field.
  PlaceJobInput jobInput() const;
  const std::string& outDir() const { return outDir_; }

 private:
  struct Snapshot {
    PlaceState state;
    std::shared_ptr<const PlaceDisplay> display;
    std::chrono::steady_clock::time_point changedAt;
  };
  struct Rendered {
    std::string png;
    Json counts;
    std::shared_ptr<const std::vector<LensletFirstHit>> lensletHits;  // level 0, for the diagram
    double serverMs = 0.0;
    std::string error;
  };

  void workerLoop();
  void diagramLoop();
  // Records a finished image's server time (call with mutex_ held).
  void recordLatency(ImageKind kind, Rendered& r, const Snapshot& snap);
  std::optional<ImageKind> nextWork(std::unique_lock<std::mutex>& lock);
  Rendered render(ImageKind kind, const Snapshot& snap);  // levels 0-2
  Rendered renderDiagram(const Snapshot& snap, std::shared_ptr<const std::vector<LensletFirstHit>> hits);
  // The kept level 0 or diagram of `revision`, or null (call with mutex_ held).
  const Rendered* level0Of(uint64_t revision) const;
  const Rendered* diagramOf(uint64_t revision) const;
  std::shared_ptr<const PlaceDisplay> displayFor(const PlaceState& s) const;

  LoadedField field_;
  std::string fieldPath_, outDir_;
  std::vector<std::string> displays_;
  PlaceState defaults_;
  uint64_t seed_;
  std::chrono::milliseconds quiet_;

  mutable std::mutex mutex_;
  std::condition_variable changed_;  // the state, a result, or stop
  Snapshot current_;
  std::map<int, Rendered> results_;   // of current_'s revision: levels 1 and 2
  // Level 0 is short and the page needs frames while the user drags: once started it is
  // finished and kept for its revision, even when the state has moved on meanwhile.
  std::optional<uint64_t> level0InFlight_;
  std::optional<std::pair<uint64_t, Rendered>> lastLevel0_;  // the newest finished, by revision
  std::optional<uint64_t> diagramInFlight_;                    // the same for the diagram
  std::optional<std::pair<uint64_t, Rendered>> lastDiagram_;
  uint64_t diagramAsked_ = 0;         // the newest revision a request asked the diagram of
  std::optional<double> exposure_;    // fixed by the first level-0 frame, so brightness holds still
  std::vector<std::deque<double>> latencies_;
  bool stop_ = false;
  std::unique_ptr<PlaceJobs> jobs_;
  std::thread worker_, diagramWorker_;
};

}  // namespace inim
