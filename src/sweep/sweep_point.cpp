#include "sweep/sweep_point.h"

#include <filesystem>

#include "core/content_hash.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/interrupt.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "display/display.h"
#include "sweep/fig11_settings_json.h"

namespace inim {
namespace fs = std::filesystem;

namespace {

constexpr const char* kResultFormat = "inim sweep point 1";
// fig11's outputs whose bytes result.json records (those present).
const char* const kHashedOutputs[] = {"fig11/metrics.json", "fig11/budget.json"};

void writeIfChanged(OutputSet& out, const std::string& path, const std::string& text) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec) && readInputFile(path) == text) return;
  writeTextFile(out.add(path), text);
}

Json pointMetricsJson(const ImageMetrics& m) {
  return {{"psnr_db", m.psnrDb}, {"ssim", m.ssim}, {"de_mean", m.deltaE.mean},
          {"de_p95", m.deltaE.p95}, {"de_max", m.deltaE.max}, {"pixels", m.pixels}};
}

Json poseJson(const Fig11View& v, const PoseBudget* budget) {
  Json j = pointMetricsJson(v.metrics);
  j["pose"] = v.name;
  j["de_mean_band_limited"] = v.bandLimitedMetrics.deltaE.mean;
  if (budget) {
    j["noise_floor_de"] = budget->noiseFloor.deltaE.mean;
    Json rungs = Json::array();  // in the budget's order
    for (const auto* list : {&budget->ladder, &budget->removeOne})
      for (const RungResult& r : *list)
        rungs.push_back({{"rung", r.rung.name}, {"de_mean", r.skipped ? Json() : Json(r.metrics.deltaE.mean)}});
    j["budget"] = rungs;
  }
  return j;
}

PlacementOverride placementFromJson(const JsonObject& o) {
  PlacementOverride p;
  if (o.has("scale")) p.scale = o.vec3("scale");
  if (o.has("rotate_deg")) p.rotateDeg = o.vec3("rotate_deg");
  if (o.has("translate_mm")) p.translateMm = o.vec3("translate_mm");
  o.rejectUnknown();
  return p;
}

Json readPointJson(const std::string& dir) {
  const std::string path = (fs::path(dir) / "point.json").string();
  if (!fs::exists(path)) throw InputError(path, "", "missing", "a point of this sweep (inim sweep --plan writes it)");
  return readJsonFile(path);
}

// The point's fig11 settings from its point.json.
Fig11Settings pointSettings(const std::string& dir, const Json& point) {
  const std::string file = (fs::path(dir) / "point.json").string();
  const JsonObject config(point.at("config"), file, "config");
  Fig11Settings s = fig11SettingsFromJson(config.object("fig11"));
  s.display = loadDisplay((fs::path(dir) / "display.json").string());
  config.raw("display"), config.raw("display_file");
  s.fieldPath = config.string("field");
  s.camera = config.string("camera");
  s.placement = placementFromJson(config.object("placement"));
  config.rejectUnknown();
  s.outDir = (fs::path(dir) / "fig11").string();
  return s;
}

}  // namespace

std::string sweepPointDir(const std::string& sweepDir, const std::string& id) {
  return (fs::path(sweepDir) / "points" / id).string();
}

std::string sweepPointCommand(const std::string& program, const std::string& sweepDir, const std::string& id) {
  return program + " sweep --out " + sweepDir + " --point " + id;
}

void writeSweepPointFiles(const std::string& sweepDir, const SweepPoint& p, const std::string& program) {
  const std::string dir = sweepPointDir(sweepDir, p.id);
  Json j;
  j["id"] = p.id;
  j["index"] = p.index;
  j["values"] = Json::object();
  for (const auto& [k, v] : p.values) j["values"][k] = v;
  j["choices"] = Json::object();
  for (const auto& [k, v] : p.choices) j["choices"][k] = v;
  j["config"] = p.config;
  j["command"] = sweepPointCommand(program, sweepDir, p.id);
  OutputSet out;
  writeIfChanged(out, (fs::path(dir) / "point.json").string(), j.dump(2) + "\n");
  writeIfChanged(out, (fs::path(dir) / "display.json").string(), p.config.at("display").dump(2) + "\n");
  out.commit();
}

Json recordedSweepResult(const std::string& sweepDir, const std::string& id) {
  const fs::path path = fs::path(sweepPointDir(sweepDir, id)) / "result.json";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return nullptr;
  try {
    return readJsonFile(path.string());
  } catch (const std::exception&) {
    return nullptr;
  }
}

Json completeSweepResult(const std::string& sweepDir, const std::string& id) {
  const std::string dir = sweepPointDir(sweepDir, id);
  Json r = recordedSweepResult(sweepDir, id);
  try {
    if (r.is_null() || r.at("format") != kResultFormat || r.at("status") != "ok") return nullptr;
    if (r.at("point_sha256") != fileSha256((fs::path(dir) / "point.json").string())) return nullptr;
    for (const auto& [name, hash] : r.at("files").items()) {
      const fs::path f = fs::path(dir) / name;
      std::error_code ec;
      if (!fs::is_regular_file(f, ec) || fileSha256(f.string()) != hash.get<std::string>()) return nullptr;
    }
    return r;
  } catch (const std::exception&) {
    return nullptr;
  }
}

Json runSweepPoint(const std::string& sweepDir, const std::string& id, int threads, const std::string& referenceCache) {
  const std::string dir = sweepPointDir(sweepDir, id);
  const Json point = readPointJson(dir);
  std::error_code ec;
  fs::remove(fs::path(dir) / "result.json", ec);  // until this run's is written, the point is partial
  const ThreadLimit limit(threads);
  const auto start = std::chrono::steady_clock::now();
  Json result;
  result["format"] = kResultFormat;
  result["id"] = id;
  result["point_sha256"] = fileSha256((fs::path(dir) / "point.json").string());
  result["files"] = Json::object();
  try {
    Fig11Settings s = pointSettings(dir, point);
    s.referenceCacheDir = referenceCache;
    s.referenceCache = referenceCache != "off";
    const Fig11Result r = runFig11(s);
    result["status"] = "ok";
    result["eia_seconds"] = r.eiaSeconds;
    int cached = 0, rendered = 0;
    result["poses"] = Json::array();
    for (const Fig11View& v : r.views) {
      (v.referenceCached ? cached : rendered) += 1;
      if (!v.hasMetrics) continue;
      const PoseBudget* b = nullptr;
      for (const PoseBudget& pb : r.budgets)
        if (pb.pose == v.name) b = &pb;
      result["poses"].push_back(poseJson(v, b));
    }
    result["references"] = {{"cached", cached}, {"rendered", rendered}};
    for (const char* name : kHashedOutputs) {
      const fs::path f = fs::path(dir) / name;
      if (fs::exists(f)) result["files"][name] = fileSha256(f.string());
    }
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    result["status"] = "failed";
    result["error"] = withOutputNames(e.what());
  }
  result["seconds"] = secondsSince(start);
  OutputSet out;
  writeTextFile(out.add((fs::path(dir) / "result.json").string()), result.dump(2) + "\n");
  out.commit();
  return result;
}

void recordSweepFailure(const std::string& sweepDir, const std::string& id, const std::string& error) {
  const std::string dir = sweepPointDir(sweepDir, id);
  Json result = {{"format", kResultFormat}, {"id", id}, {"status", "failed"}, {"error", error}, {"files", Json::object()}};
  OutputSet out;
  writeTextFile(out.add((fs::path(dir) / "result.json").string()), result.dump(2) + "\n");
  out.commit();
}

}  // namespace inim
