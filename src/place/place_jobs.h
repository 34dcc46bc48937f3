#pragma once
// The placement page's writes (docs/place-api.md): the run file, the EIA, the Zemax SDF and a
// predicted camera view, each a job run in order on one thread, writing only into the output
// folder chosen at start-up, through temporaries renamed into place when complete.
//
//   PlaceJobs jobs("out/place");
//   uint64_t id = jobs.submit(parseJsonText(R"({"what": "run", "name": "a"})", "request body"), input);
//   Json status = *jobs.get(id);  // {"state": "done", "files": ["a.json"], ...}
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/json_config.h"
#include "place/place_state.h"

namespace inim {

// What a job needs from the session at the moment it is asked for.
struct PlaceJobInput {
  PlaceState state;
  std::string fieldPath;
  uint64_t seed = 1;
};

// A file name from the page: letters, digits, '.', '-' and '_', at most 100 characters, not
// starting with '.' (so no "..", no '/', no absolute path). InputError naming `key` otherwise.
std::string sanitizeOutputName(const std::string& name, const std::string& key = "name");

// The job bodies, callable alone (tests): each writes into `outDir` and returns the names written.
std::vector<std::string> writeRunFileJob(const PlaceJobInput& in, const std::string& outDir, const std::string& name);
std::vector<std::string> writeEiaJob(const PlaceJobInput& in, const std::string& outDir, const std::string& name,
                                     bool sdf);
struct PredictRequest {
  double angleDeg = 0.0;  // the display turned about its vertical axis (inim view --rot-h-deg)
  int width = 324;
  std::string name = "predict";
};
// The EIA of the state (in a temporary folder, removed after), then `inim view --reference`
// at the angle: NAME.png and NAME_reference.png, NAME_error.png, NAME_metrics.json, the EXRs.
std::vector<std::string> predictViewJob(const PlaceJobInput& in, const std::string& outDir, const PredictRequest& p,
                                        Json& metrics, const std::function<void(const std::string&, double)>& stage);

class PlaceJobs {
 public:
  explicit PlaceJobs(std::string outDir);
  ~PlaceJobs();  // waits for the running job; queued ones are dropped
  PlaceJobs(const PlaceJobs&) = delete;
  PlaceJobs& operator=(const PlaceJobs&) = delete;

  // {"what": "run" | "eia" | "sdf", "name": N} or, with `predict`, {"angle_deg", "width", "name"}.
  // InputError (a 400) before anything is queued.
  uint64_t submit(const Json& body, const PlaceJobInput& in, bool predict);
  Json list() const;
  std::optional<Json> get(uint64_t id) const;

 private:
  struct Job {
    uint64_t id = 0;
    std::string what, state = "queued", stage, error;
    double progress = 0.0;
    std::vector<std::string> files;
    Json metrics;
  };
  struct Outcome {
    std::vector<std::string> files;
    Json metrics;
  };
  using Work = std::function<Outcome(uint64_t id)>;
  static Json toJson(const Job& j);
  void loop();
  void setStage(uint64_t id, const std::string& stage, double progress);

  std::string outDir_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::map<uint64_t, Job> jobs_;
  std::deque<std::pair<uint64_t, Work>> queue_;
  uint64_t nextId_ = 1;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace inim
