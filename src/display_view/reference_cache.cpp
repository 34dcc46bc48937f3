#include "display_view/reference_cache.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <thread>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/content_hash.h"
#include "core/interrupt.h"
#include "core/image.h"
#include "core/json_config.h"
#include "core/output_file.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

constexpr const char* kCacheFormat = "inim reference cache 2";

// Every string in a JSON document, depth first.
void collectStrings(const Json& j, std::vector<std::string>& out) {
  if (j.is_string()) out.push_back(j.get<std::string>());
  else if (j.is_object() || j.is_array())
    for (const auto& v : j) collectStrings(v, out);
}

// The file a scene's string names, as the loaders find it: beside the scene, else in the data folder.
std::optional<std::string> namedFile(const fs::path& dir, const std::string& s) {
  if (s.empty() || s.size() > 4096) return std::nullopt;
  try {  // most strings are not file names (notes, names): those the filesystem refuses too
    std::error_code ec;
    const fs::path beside = dir / s;
    if (fs::is_regular_file(beside, ec)) return beside.string();
    if (fs::path(s).is_relative()) {
      const std::string data = dataPath(s);
      if (fs::is_regular_file(data, ec)) return data;
    }
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

void addCamera(Sha256& h, const CameraModel& camera) {
  h.addValue(int(camera.kind()));
  h.addValue(camera.width());
  h.addValue(camera.height());
  h.addValue(camera.isDispersive());
  // Its rays on a 9 x 9 grid of pixel positions and 4 lens samples, at three wavelengths.
  for (float lambda : {450.0f, 550.0f, 650.0f})
    for (int j = 0; j <= 8; ++j)
      for (int i = 0; i <= 8; ++i)
        for (int k = 0; k < 4; ++k) {
          Ray r;
          const Vec2 pixel(camera.width() * (0.01f + 0.98f * i / 8.0f), camera.height() * (0.01f + 0.98f * j / 8.0f));
          const float w = camera.generateRay(pixel, Vec2(0.2f + 0.2f * k, 0.8f - 0.2f * k), lambda, r);
          h.addValue(w);
          if (w > 0.0f) h.addValue(r.o), h.addValue(r.d);
        }
}

void addSensor(Sha256& h, const CameraSensor& sensor) {
  for (int nm = 360; nm <= 830; ++nm) h.addValue(sensor.response(double(nm)));
  h.addValue(sensor.xyzToCameraRgb());
}

std::string thisHost() {
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  return host;
}

std::string temporaryTag() { return ".tmp-" + thisHost() + "-" + std::to_string(getpid()); }

std::string entryPath(const std::string& dir, const std::string& key, const char* ext) {
  return (fs::path(dir) / (key + ext)).string();
}

}  // namespace

std::string referenceCacheDir() {
  if (const char* off = std::getenv("INIM_REFERENCE_CACHE"); off && std::string(off) == "0") return "";
  return (fs::path(cacheDirs().front()) / "references").string();
}

std::string fieldContentKey(const std::string& path) {
  Sha256 h;
  h.add(fileSha256(path));
  if (fs::path(path).extension() == ".json") {
    std::vector<std::string> strings;
    collectStrings(readJsonFile(path), strings);
    const fs::path dir = fs::path(path).parent_path();
    for (const std::string& s : strings)
      if (const auto f = namedFile(dir, s)) {
        h.add(s);
        h.add(fileSha256(*f));
      }
  }
  return h.hex();
}

std::string referenceCacheKey(const std::string& fieldKey, const Transform& fieldToDisplay, const CameraModel& camera,
                              const CameraSensor& sensor, const ReferenceSettings& s) {
  Sha256 h;
  h.add(kCacheFormat);
  h.add(programSha256());
  h.add(fieldKey);
  h.addValue(fieldToDisplay.matrix());
  addCamera(h, camera);
  addSensor(h, sensor);
  h.addValue(s.spp);
  h.addValue(s.seed);
  h.addValue(int(s.dispersion));
  h.addValue(s.depth);
  h.addValue(s.sppElsewhere);
  h.addValue(s.fullSamples != nullptr);
  if (s.fullSamples) h.add(s.fullSamples->data(), s.fullSamples->size());
  return h.hex();
}

std::optional<ViewResult> loadCachedReference(const std::string& dir, const std::string& key) {
  const std::string exr = entryPath(dir, key, ".exr"), json = entryPath(dir, key, ".json");
  std::error_code ec;
  if (!fs::is_regular_file(exr, ec) || !fs::is_regular_file(json, ec)) return std::nullopt;
  try {
    ViewResult r;
    r.image = readImage(exr);
    const Json j = readJsonFile(json);
    if (j.at("format").get<std::string>() != kCacheFormat || j.at("key").get<std::string>() != key) return std::nullopt;
    if (j.at("exr_sha256").get<std::string>() != fileSha256(exr)) return std::nullopt;  // verified, not assumed
    r.stats.tracedRays = j.at("traced_rays").get<uint64_t>();
    r.stats.emittingRays = j.at("hit_rays").get<uint64_t>();
    r.stats.raysPerSample = j.at("rays_per_sample").get<int>();
    r.stats.dispersive = j.at("dispersive").get<bool>();
    r.stats.seconds = 0.0;
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // damaged: rendered again and overwritten
  }
}

void storeCachedReference(const std::string& dir, const std::string& key, const ViewResult& r) {
  try {
    fs::create_directories(dir);
    // Temporaries keep their extension: the image writer picks the format by it. Tagged by host
    // and process: array tasks on several nodes may write one entry to a shared file system.
    const std::string tag = temporaryTag();
    const std::string exr = entryPath(dir, key, ".exr"), json = entryPath(dir, key, ".json");
    const std::string exrTmp = entryPath(dir, key + tag, ".exr"), jsonTmp = entryPath(dir, key + tag, ".json");
    writeImage(r.image, exrTmp);
    const Json j{{"format", kCacheFormat},       {"key", key}, {"exr_sha256", fileSha256(exrTmp)},
                 {"traced_rays", r.stats.tracedRays}, {"hit_rays", r.stats.emittingRays},
                 {"rays_per_sample", r.stats.raysPerSample}, {"dispersive", r.stats.dispersive},
                 {"render_seconds", r.stats.seconds}};
    {
      std::ofstream out(jsonTmp);
      out << j.dump(2) << "\n";
      if (!out) throw std::runtime_error("write");
    }
    fs::rename(jsonTmp, json);
    fs::rename(exrTmp, exr);  // the image last: its presence marks a whole entry
  } catch (const std::exception&) {
    // A full disk or a read-only cache: the run goes on without the entry.
    std::error_code ec;
    for (const char* ext : {".exr", ".json"}) fs::remove(entryPath(dir, key + temporaryTag(), ext), ec);
  }
}

ReferenceClaim& ReferenceClaim::operator=(ReferenceClaim&& o) noexcept {
  if (this != &o) {
    ReferenceClaim old(std::move(*this));
    lock_ = std::exchange(o.lock_, {});
  }
  return *this;
}

ReferenceClaim::~ReferenceClaim() {
  std::error_code ec;
  if (!lock_.empty()) fs::remove(lock_, ec);
}

namespace {

// A claim nobody will finish: its process is gone (on this host), or it is older than `staleSeconds`.
bool staleClaim(const std::string& lock, double staleSeconds) {
  std::ifstream in(lock);
  std::string host;
  long pid = 0;
  if (in >> host >> pid && host == thisHost() && pid > 0 && kill(pid_t(pid), 0) != 0 && errno == ESRCH) return true;
  std::error_code ec;
  const auto written = fs::last_write_time(lock, ec);
  if (ec) return false;  // gone meanwhile: the next try sees
  const double age = std::chrono::duration<double>(fs::file_time_type::clock::now() - written).count();
  return age > staleSeconds;
}

}  // namespace

std::optional<ViewResult> loadOrClaimReference(const std::string& dir, const std::string& key, ReferenceClaim& claim,
                                               double staleSeconds) {
  const std::string lock = entryPath(dir, key, ".lock");
  std::error_code ec;
  fs::create_directories(dir, ec);
  for (;;) {
    if (std::optional<ViewResult> cached = loadCachedReference(dir, key)) return cached;
    const int fd = open(lock.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      const std::string owner = thisHost() + " " + std::to_string(getpid()) + "\n";
      const bool written = write(fd, owner.data(), owner.size()) == ssize_t(owner.size());
      close(fd);
      (void)written;  // an unreadable claim is still a claim; it goes stale by age
      claim = ReferenceClaim(lock);
      // Rendered by the run that just let its claim go: read it, not render it again.
      if (std::optional<ViewResult> cached = loadCachedReference(dir, key)) return cached;
      return std::nullopt;
    }
    if (errno != EEXIST) return std::nullopt;  // a read-only cache: render without a claim
    if (staleClaim(lock, staleSeconds)) {
      fs::remove(lock, ec);
      continue;
    }
    throwIfInterrupted();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

}  // namespace inim
