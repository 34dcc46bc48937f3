#include "place/place_jobs.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/output_file.h"
#include "runs/eia_run.h"
#include "runs/view_reference.h"

namespace inim {

namespace fs = std::filesystem;

std::string sanitizeOutputName(const std::string& name, const std::string& key) {
  bool ok = !name.empty() && name.size() <= 100 && name[0] != '.';
  for (char c : name)
    ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_');
  if (!ok)
    throw InputError("request body", key, "\"" + name.substr(0, 100) + "\"",
                     "1-100 letters, digits, '.', '-' or '_', not starting with '.'");
  return name;
}

namespace {

// `inim eia --run` with the state's run file: the same settings, from the same defaults.
EiaRunSettings eiaSettings(const PlaceJobInput& in) {
  EiaRunSettings e;
  e.displayPath = in.state.display;
  e.layout.layout = in.state.layout;
  e.layout.viewingDistanceMm = in.state.viewingDistanceMm;
  e.fieldPath = in.fieldPath;
  e.placement = in.state.placement;
  e.synthesis.vcpMm = in.state.vcpMm;
  e.synthesis.seed = in.seed;
  e.synthesis.progress = false;
  return e;
}

std::string join(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

}  // namespace

std::vector<std::string> writeRunFileJob(const PlaceJobInput& in, const std::string& outDir, const std::string& name) {
  OutputSet outputs;
  writeTextFile(outputs.add(join(outDir, name + ".json")), runFileJson(in.state, in.fieldPath).dump(2) + "\n");
  outputs.commit();
  return {name + ".json"};
}

std::vector<std::string> writeEiaJob(const PlaceJobInput& in, const std::string& outDir, const std::string& name,
                                     bool sdf) {
  EiaRunSettings e = eiaSettings(in);
  e.out = join(outDir, name + ".exr");
  e.png = join(outDir, name + ".png");
  if (sdf) e.sdf = join(outDir, name + ".sdf");
  runEia(e);
  std::vector<std::string> files{name + ".exr", name + ".png"};
  if (sdf) files.push_back(name + ".sdf");
  return files;
}

std::vector<std::string> predictViewJob(const PlaceJobInput& in, const std::string& outDir, const PredictRequest& p,
                                        Json& metrics, const std::function<void(const std::string&, double)>& stage) {
  // The EIA goes to a private temporary folder: only the view and its comparison are outputs.
  const fs::path tmp = fs::temp_directory_path() / ("inim-place-" + std::to_string(::getpid()) + "-" + p.name);
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  struct Cleanup {
    fs::path dir;
    ~Cleanup() { std::error_code ec; fs::remove_all(dir, ec); }
  } cleanup{tmp};
  stage("EIA", 0.1);
  EiaRunSettings e = eiaSettings(in);
  e.out = (tmp / "eia.exr").string();
  runEia(e);

  stage("view and reference", 0.5);
  ViewRunSettings v;
  v.camera.rotHDeg = p.angleDeg;
  v.camera.width = p.width;
  v.camera.out = join(outDir, p.name + ".exr");
  v.displayPath = in.state.display;
  v.layout = e.layout;
  v.eiaPath = e.out;
  v.view.seed = in.seed;
  v.view.progress = false;
  ViewReferenceSettings rs;
  rs.fieldPath = in.fieldPath;
  rs.placement = in.state.placement;
  rs.referenceSpp = 4;
  rs.budget = false;
  const ViewReferenceResult r = runViewWithReference(v, rs);
  auto finiteOrNull = [](double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); };
  metrics = {{"psnr_db", finiteOrNull(r.metrics.psnrDb)}, {"ssim", finiteOrNull(r.metrics.ssim)},
             {"ciede2000_mean", finiteOrNull(r.metrics.deltaE.mean)},
             {"ciede2000_p95", finiteOrNull(r.metrics.deltaE.p95)}, {"has_metrics", r.hasMetrics}};
  std::vector<std::string> files;
  for (const std::string& w : r.written) files.push_back(fs::path(w).filename().string());
  return files;
}

PlaceJobs::PlaceJobs(std::string outDir) : outDir_(std::move(outDir)), thread_([this] { loop(); }) {}

PlaceJobs::~PlaceJobs() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

uint64_t PlaceJobs::submit(const Json& body, const PlaceJobInput& in, bool predict) {
  if (!body.is_object()) throw InputError("request body", "", jsonValueText(body), "a JSON object");
  JsonObject o(body, "request body", "");
  std::string what = "predict";
  Work work;
  if (predict) {
    PredictRequest p;
    p.angleDeg = o.number("angle_deg", 0.0);
    if (!(std::abs(p.angleDeg) <= 40.0)) o.fail("angle_deg", jsonValueText(o.raw("angle_deg")), "a number in [-40, 40]");
    p.width = o.integer("width", 324);
    if (p.width < 64 || p.width > 1024) o.fail("width", jsonValueText(o.raw("width")), "a whole number in [64, 1024]");
    p.name = sanitizeOutputName(o.string("name", "predict"));
    work = [this, in, p](uint64_t id) {
      Outcome out;
      out.files = predictViewJob(in, outDir_, p, out.metrics,
                                 [this, id](const std::string& s, double f) { setStage(id, s, f); });
      return out;
    };
  } else {
    what = o.choice("what", {"run", "eia", "sdf"});
    const std::string name = sanitizeOutputName(o.string("name", "placement"));
    work = [this, in, what, name](uint64_t id) {
      setStage(id, what == "run" ? "writing" : "EIA synthesis", 0.1);
      Outcome out;
      out.files = what == "run" ? writeRunFileJob(in, outDir_, name) : writeEiaJob(in, outDir_, name, what == "sdf");
      return out;
    };
  }
  o.rejectUnknown();
  std::lock_guard<std::mutex> lock(mutex_);
  const uint64_t id = nextId_++;
  Job& j = jobs_[id];
  j.id = id;
  j.what = what;
  queue_.emplace_back(id, std::move(work));
  wake_.notify_all();
  return id;
}

void PlaceJobs::setStage(uint64_t id, const std::string& stage, double progress) {
  std::lock_guard<std::mutex> lock(mutex_);
  Job& j = jobs_[id];
  j.stage = stage;
  j.progress = progress;
}

void PlaceJobs::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    auto [id, work] = std::move(queue_.front());
    queue_.pop_front();
    jobs_[id].state = "running";
    lock.unlock();
    Outcome out;
    std::string error;
    try {
      out = work(id);
    } catch (const Interrupted&) {
      error = "interrupted";
    } catch (const std::exception& e) {
      error = e.what();
    }
    lock.lock();
    Job& j = jobs_[id];
    j.state = error.empty() ? "done" : "failed";
    j.error = error;
    j.progress = error.empty() ? 1.0 : j.progress;
    j.stage = error.empty() ? "done" : j.stage;
    j.files = std::move(out.files);
    j.metrics = std::move(out.metrics);
  }
}

Json PlaceJobs::toJson(const Job& j) {
  return {{"id", j.id},       {"what", j.what},   {"state", j.state},     {"stage", j.stage},
          {"progress", j.progress}, {"files", j.files}, {"error", j.error}, {"metrics", j.metrics}};
}

Json PlaceJobs::list() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Json a = Json::array();
  for (const auto& [id, j] : jobs_) a.push_back(toJson(j));
  return a;
}

std::optional<Json> PlaceJobs::get(uint64_t id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  return toJson(it->second);
}

}  // namespace inim
