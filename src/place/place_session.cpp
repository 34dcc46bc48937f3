#include "place/place_session.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "place/place_preview.h"
#include "display/layout_override.h"
#include "synthesis/preview.h"
#include "runs/run_file.h"
#include "core/file_kinds.h"

namespace inim {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

std::string absolutePath(const std::string& p) { return fs::absolute(fs::path(p)).lexically_normal().string(); }

// The display files the page may choose: optics/displays/*.json and the one given.
std::vector<std::string> displayFiles(const std::string& given) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dataPath("optics/displays"), ec))
    if (isFileKind(e.path().string(), FileKind::Json)) files.push_back(absolutePath(e.path().string()));
  std::sort(files.begin(), files.end());
  if (std::find(files.begin(), files.end(), given) == files.end()) files.push_back(given);
  return files;
}

const char* kindName(ImageKind k) {
  static const char* names[] = {"level0", "level1", "level2", "diagram"};
  return names[int(k)];
}

Json countsJson(const PreviewCounts& c) {
  return {{"real", c.real}, {"virtual", c.virtualHits}, {"on_plane", c.onPlane}, {"missed", c.missed}};
}

Json statsJson(std::deque<double> v) {
  if (v.empty()) return {{"count", 0}};
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return v[std::min(v.size() - 1, size_t(q * double(v.size())))]; };
  return {{"count", v.size()}, {"median_ms", at(0.5)}, {"p95_ms", at(0.95)}, {"max_ms", v.back()}};
}

}  // namespace

PlaceSession::PlaceSession(const PlaceOptions& o) : PlaceSession(o, LoadedField{}) {}

PlaceSession::PlaceSession(const PlaceOptions& o, LoadedField given)
    : seed_(o.seed), quiet_(o.quietMs), latencies_(kImageKinds) {
  const RunFile run = o.runPath.empty() ? RunFile{} : loadRunFile(o.runPath);
  fieldPath_ = absolutePath(!o.fieldPath.empty() ? o.fieldPath : run.scene.value_or(defaultScenePath()));
  field_ = given.field ? std::move(given)
                       : loadField(fieldPath_, o.fieldPath.empty() && run.scene ? "scene (" + o.runPath + ")" : "field");
  outDir_ = absolutePath(o.outDir);

  PlaceState s;
  s.display = absolutePath(displayPathOrDefault(!o.displayPath.empty() ? o.displayPath : run.display.value_or("")));
  const Display d = loadDisplay(s.display);
  s.layout = run.layout.value_or(d.layout == EiLayoutKind::ToedIn ? "toed-in" : "parallel");
  s.viewingDistanceMm = run.viewingDistanceMm.value_or(d.viewingDistanceMm.value_or(350.0));
  s.vcpMm = run.vcpMm.value_or(s.vcpMm);
  s.placement = resolvePlacement(run.placement ? run.placement : field_.placement, {});
  displays_ = displayFiles(s.display);
  defaults_ = s;
  current_ = {s, displayFor(s), Clock::now()};
  fs::create_directories(outDir_);  // only once everything loaded: a bad start writes nothing
  jobs_ = std::make_unique<PlaceJobs>(outDir_);
  worker_ = std::thread([this] { workerLoop(); });
  diagramWorker_ = std::thread([this] { diagramLoop(); });
}

PlaceSession::~PlaceSession() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  worker_.join();
  diagramWorker_.join();
}

std::shared_ptr<const PlaceDisplay> PlaceSession::displayFor(const PlaceState& s) const {
  auto pd = std::make_shared<PlaceDisplay>();
  pd->display = loadDisplay(s.display);
  LayoutOverride lo;
  lo.layout = s.layout;
  lo.viewingDistanceMm = s.viewingDistanceMm;
  pd->layout = applyLayoutOverride(pd->display, lo);
  return pd;
}

Json PlaceSession::state() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return placeStateJson(current_.state);
}

Json PlaceSession::putState(const std::string& body) {
  const Json patch = parseJsonText(body, "request body");
  PlaceState cur;
  std::shared_ptr<const PlaceDisplay> disp;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    cur = current_.state;
    disp = current_.display;
  }
  PlaceState next = applyStatePatch(cur, patch, displays_);
  // A new display file, layout or distance is loaded and checked before the state changes.
  if (next.display != cur.display || next.layout != cur.layout || next.viewingDistanceMm != cur.viewingDistanceMm)
    disp = displayFor(next);
  std::lock_guard<std::mutex> lock(mutex_);
  next.revision = current_.state.revision + 1;
  current_ = {next, disp, Clock::now()};
  results_.clear();
  changed_.notify_all();
  return placeStateJson(next);
}

ImageAnswer PlaceSession::image(ImageKind kind, uint64_t revision, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto deadline = Clock::now() + timeout;
  ImageAnswer a;
  a.revision = revision;
  auto answer = [&a](const Rendered& r) {
    a.status = r.error.empty() ? ImageAnswer::Status::Ready : ImageAnswer::Status::Failed;
    a.png = r.png, a.counts = r.counts, a.serverMs = r.serverMs, a.error = r.error;
    return a;
  };
  if (kind == ImageKind::Diagram && revision > diagramAsked_ && revision <= current_.state.revision) {
    diagramAsked_ = revision;  // drawn once asked for: see diagramLoop
    changed_.notify_all();
  }
  while (true) {
    const bool kept = kind == ImageKind::Level0 || kind == ImageKind::Diagram;
    const Rendered* done = kind == ImageKind::Level0 ? level0Of(revision)
                           : kind == ImageKind::Diagram ? diagramOf(revision) : nullptr;
    const auto& inFlight = kind == ImageKind::Level0 ? level0InFlight_ : diagramInFlight_;
    if (revision < current_.state.revision) {
      // An older revision's level 0 or diagram is served when it was finished, waited for when
      // under way.
      if (!kept) return a.status = ImageAnswer::Status::Stale, a;
      if (done) return answer(*done);
      if (inFlight != revision) return a.status = ImageAnswer::Status::Stale, a;
    } else if (revision > current_.state.revision) {
      return a.status = ImageAnswer::Status::Future, a;
    } else if (kept) {
      if (done) return answer(*done);
    } else if (auto it = results_.find(int(kind)); it != results_.end()) {
      return answer(it->second);
    }
    if (changed_.wait_until(lock, deadline) == std::cv_status::timeout)
      return a.status = ImageAnswer::Status::Timeout, a;
  }
}

const PlaceSession::Rendered* PlaceSession::level0Of(uint64_t revision) const {
  return lastLevel0_ && lastLevel0_->first == revision ? &lastLevel0_->second : nullptr;
}

const PlaceSession::Rendered* PlaceSession::diagramOf(uint64_t revision) const {
  return lastDiagram_ && lastDiagram_->first == revision ? &lastDiagram_->second : nullptr;
}

// The next image to render for the current revision, or none (waiting until there is one).
std::optional<ImageKind> PlaceSession::nextWork(std::unique_lock<std::mutex>& lock) {
  while (!stop_) {
    if (!level0Of(current_.state.revision)) return ImageKind::Level0;
    const auto still = current_.changedAt + quiet_;
    if (Clock::now() < still) {
      changed_.wait_until(lock, still);
      continue;
    }
    for (ImageKind k : {ImageKind::Level1, ImageKind::Level2})
      if (!results_.count(int(k))) return k;
    changed_.wait(lock);
  }
  return std::nullopt;
}

void PlaceSession::workerLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (auto kind = nextWork(lock)) {
    const Snapshot snap = current_;
    if (*kind == ImageKind::Level0) level0InFlight_ = snap.state.revision;
    lock.unlock();
    Rendered r;
    bool cancelled = false;
    try {
      r = render(*kind, snap);
    } catch (const PreviewCancelled&) {
      cancelled = true;
    } catch (const Interrupted&) {  // Ctrl-C: the command is stopping the session
      cancelled = true;
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    lock.lock();
    if (*kind == ImageKind::Level0) level0InFlight_.reset();
    const bool current = snap.state.revision == current_.state.revision;
    if (cancelled || stop_ || (!current && *kind != ImageKind::Level0)) {
      changed_.notify_all();  // a request waiting for this level 0 learns it is stale
      continue;
    }
    recordLatency(*kind, r, snap);
    if (*kind == ImageKind::Level0)
      lastLevel0_ = {snap.state.revision, std::move(r)};
    else
      results_[int(*kind)] = std::move(r);
    changed_.notify_all();
  }
}

// Level 0 of this revision asked the same rays (`hits`): the diagram only draws.
PlaceSession::Rendered PlaceSession::renderDiagram(const Snapshot& snap,
                                                   std::shared_ptr<const std::vector<LensletFirstHit>> hits) {
  PreviewSettings ps;
  ps.width = 900;
  ps.seed = seed_;
  ps.cancelled = [this] {
    std::lock_guard<std::mutex> lock(mutex_);
    return stop_;
  };
  if (hits) ps.knownHits = *hits;
  const PreviewResult p = renderPlacementPreview(snap.display->layout, *field_.field, snap.state.placement.toDisplay(),
                                                 snap.state.vcpMm, ps);
  Rendered r;
  r.png = encodePng(p.image);
  r.counts = {{"real", p.real}, {"virtual", p.virtualHits}, {"on_plane", p.onPlane}, {"missed", p.missed}};
  return r;
}

void PlaceSession::recordLatency(ImageKind kind, Rendered& r, const Snapshot& snap) {
  r.serverMs = std::chrono::duration<double, std::milli>(Clock::now() - snap.changedAt).count();
  auto& lat = latencies_[size_t(kind)];
  lat.push_back(r.serverMs);
  if (lat.size() > 1000) lat.pop_front();
}

// The diagram of the newest revision whose level 0 is done (it draws that level 0's hits), in
// the time the level-0 renders leave: this thread runs at the lowest priority. It draws only a
// revision a request has asked for: drawn for every revision of a drag, even niced, it took
// cores the level-0 renders and the browser needed. Like level 0, a diagram under way is
// finished and kept for its revision while a drag goes on.
void PlaceSession::diagramLoop() {
  lowerThisThreadsPriority();
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    const Snapshot snap = current_;
    const Rendered* level0 = level0Of(snap.state.revision);
    if (diagramOf(snap.state.revision) || !level0 || diagramAsked_ < snap.state.revision) {
      changed_.wait(lock);
      continue;
    }
    diagramInFlight_ = snap.state.revision;
    const auto hits = level0->lensletHits;
    lock.unlock();
    Rendered r;
    bool cancelled = false;
    try {
      r = renderDiagram(snap, hits);
    } catch (const PreviewCancelled&) {
      cancelled = true;
    } catch (const Interrupted&) {
      cancelled = true;
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    lock.lock();
    diagramInFlight_.reset();
    if (!cancelled && !stop_) {
      recordLatency(ImageKind::Diagram, r, snap);
      lastDiagram_ = {snap.state.revision, std::move(r)};
    }
    changed_.notify_all();
  }
}

PlaceSession::Rendered PlaceSession::render(ImageKind kind, const Snapshot& snap) {
  const Transform toDisplay = snap.state.placement.toDisplay();
  const EiLayout& L = snap.display->layout;
  const uint64_t rev = snap.state.revision;
  auto cancelled = [this, rev, kind] {  // a level 0 is finished once begun
    std::lock_guard<std::mutex> lock(mutex_);
    return stop_ || (kind != ImageKind::Level0 && current_.state.revision != rev);
  };
  Rendered r;
  PreviewRequest req;
  req.level = int(kind);
  req.viewingDistanceMm = snap.state.viewingDistanceMm;
  req.onPlaneToleranceMm = 0.5 * L.lensPitchMm;
  req.seed = seed_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    req.exposure = exposure_;
  }
  const PreviewFrame f = renderPlacePreview(L, *field_.field, toDisplay, snap.state.vcpMm, req, cancelled);
  if (kind == ImageKind::Level0 && f.counts.missed < f.image.width * f.image.height) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!exposure_) exposure_ = f.exposure;
  }
  r.png = encodePng(f.image);
  r.counts = countsJson(f.counts);
  if (kind == ImageKind::Level0) r.lensletHits = std::make_shared<const std::vector<LensletFirstHit>>(f.lensletHits);
  return r;
}

Json PlaceSession::latency() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Json j;
  for (int k = 0; k < kImageKinds; ++k) j[kindName(ImageKind(k))] = statsJson(latencies_[size_t(k)]);
  return j;
}

PlaceJobInput PlaceSession::jobInput() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {current_.state, fieldPath_, seed_};
}

Json PlaceSession::info() const {
  std::lock_guard<std::mutex> lock(mutex_);
  const PlaceDisplay& pd = *current_.display;
  const EiLayout& L = pd.layout;
  Json f = {{"path", fieldPath_}, {"kind", fieldKindName(field_.kind)}};
  Point3d blo, bhi;
  if (boundsInFrame(*field_.field, current_.state.placement.toDisplay(), blo, bhi))
    f["bounds_mm"] = {{blo.x, blo.y, blo.z}, {bhi.x, bhi.y, bhi.z}};
  const AreaMm a = L.activeArea();
  Json displays = Json::array();
  for (const auto& d : displays_) displays.push_back({{"path", d}, {"name", fs::path(d).stem().string()}});
  const double s0 = defaults_.placement.scale.x, half = 0.5 * std::max(a.x1 - a.x0, a.y1 - a.y0);
  Json levels = Json::array();
  levels.push_back({{"level", 0}, {"width", L.eiCols}, {"height", L.eiRows}, {"what", "one ray per lenslet"}});
  levels.push_back({{"level", 1}, {"width", 4 * L.eiCols}, {"height", 4 * L.eiRows}, {"what", "4 x 4 rays per lenslet"}});
  levels.push_back({{"level", 2}, {"what", "camera at the viewing distance"}});
  return {{"field", f},
          {"display", {{"path", current_.state.display}, {"name", pd.display.name}, {"lenslets", {L.eiCols, L.eiRows}},
                       {"pitch_mm", L.lensPitchMm}, {"gap_mm", L.gapMm}, {"panel_px", {L.panelW, L.panelH}},
                       {"area_mm", {a.x1 - a.x0, a.y1 - a.y0}}}},
          {"displays", displays},
          {"out_dir", outDir_},
          {"defaults", placeStateJson(defaults_)},
          {"sliders", {{"translate_mm", {-2.0 * half, 2.0 * half}}, {"rotate_deg", {-180, 180}},
                       {"scale", {s0 / 10.0, s0 * 10.0}}, {"vcp_mm", {-2.0 * half, 4.0 * half}},
                       {"viewing_distance_mm", {100, 2000}}}},
          {"levels", levels},
          {"on_plane_tolerance_mm", 0.5 * L.lensPitchMm}};
}

}  // namespace inim
