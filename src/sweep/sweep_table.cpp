#include "sweep/sweep_table.h"

#include <algorithm>

#include "analysis/csv.h"
#include "sweep/sweep_point.h"

namespace inim {

namespace {

const std::vector<std::string> kPoseMetrics = {"psnr_db", "ssim", "de_mean", "de_p95", "de_max",
                                               "de_mean_band_limited", "noise_floor_de"};

std::optional<double> numberOrNone(const Json& j, const std::string& key) {
  if (!j.contains(key) || !j[key].is_number()) return std::nullopt;
  return j[key].get<double>();
}

// A pose's metric by its column name: budget_<rung> from the budget's list.
std::optional<double> poseMetric(const Json& pose, const std::string& name) {
  if (name.rfind("budget_", 0) != 0) return numberOrNone(pose, name);
  for (const Json& rung : pose.value("budget", Json::array()))
    if ("budget_" + rung.value("rung", "") == name) return numberOrNone(rung, "de_mean");
  return std::nullopt;
}

}  // namespace

const SweepRow* SweepTable::row(const SweepPoint& point, const std::string& pose) const {
  for (const SweepRow& r : rows)
    if (r.point == &point && r.pose == pose) return &r;
  return nullptr;
}

int SweepTable::metric(const std::string& name) const {
  const auto it = std::find(metricNames.begin(), metricNames.end(), name);
  return it == metricNames.end() ? -1 : int(it - metricNames.begin());
}

SweepTable collectSweepTable(const std::string& sweepDir, const std::vector<SweepPoint>& points) {
  SweepTable t;
  t.metricNames = kPoseMetrics;
  std::vector<Json> results;
  for (const SweepPoint& p : points) {
    Json r = completeSweepResult(sweepDir, p.id);
    SweepPointStatus st{&p, "ok", "", 0.0, 0, 0};
    if (r.is_null()) {
      const Json recorded = recordedSweepResult(sweepDir, p.id);
      const bool failed = !recorded.is_null() && recorded.value("status", "") == "failed";
      st.status = failed ? "failed" : "missing";
      st.error = failed ? recorded.value("error", "") : "";
    } else {
      st.seconds = r.value("seconds", 0.0);
      st.referencesCached = r["references"].value("cached", 0);
      st.referencesRendered = r["references"].value("rendered", 0);
      for (const Json& pose : r["poses"])
        for (const Json& rung : pose.value("budget", Json::array()))
          if (t.metric("budget_" + rung.value("rung", "")) < 0) t.metricNames.push_back("budget_" + rung.value("rung", ""));
    }
    t.cached += st.referencesCached;
    t.rendered += st.referencesRendered;
    t.points.push_back(st);
    results.push_back(std::move(r));
  }
  double floorSum = 0.0;
  int floorCount = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Json& r = results[i];
    if (r.is_null()) {
      t.rows.push_back({&points[i], t.points[i].status, "", std::vector<std::optional<double>>(t.metricNames.size())});
      continue;
    }
    for (const Json& pose : r["poses"]) {
      SweepRow row{&points[i], "ok", pose.value("pose", ""), {}};
      if (t.firstPose.empty()) t.firstPose = row.pose;
      for (const std::string& m : t.metricNames) row.metrics.push_back(poseMetric(pose, m));
      if (row.pose == t.firstPose && row.metrics[t.metric("noise_floor_de")])
        floorSum += *row.metrics[t.metric("noise_floor_de")], ++floorCount;
      t.rows.push_back(std::move(row));
    }
  }
  if (floorCount > 0) t.noiseFloor = floorSum / floorCount;
  return t;
}

std::string sweepTableCsv(const SweepTable& t, const std::vector<SweepPoint>& points) {
  std::vector<std::string> header = {"point", "index"};
  const SweepPoint* first = points.empty() ? nullptr : &points[0];
  if (first) {
    for (const auto& [name, label] : first->choices) header.push_back(name);
    for (const auto& [path, v] : first->values) header.push_back(path);
  }
  header.push_back("status");
  header.push_back("pose");
  for (const std::string& m : t.metricNames) header.push_back(m);
  std::vector<std::vector<std::string>> rows;
  for (const SweepRow& r : t.rows) {
    std::vector<std::string> row = {r.point->id, std::to_string(r.point->index)};
    for (const auto& [name, label] : r.point->choices) row.push_back(label);
    for (const auto& [path, v] : r.point->values) row.push_back(csvNumber(v));
    row.push_back(r.status);
    row.push_back(r.pose);
    for (const auto& m : r.metrics) row.push_back(m ? csvNumber(*m) : "");
    rows.push_back(std::move(row));
  }
  return csvText(header, rows);
}

Json sweepTableJson(const SweepTable& t) {
  Json j;
  j["rows"] = Json::array();
  for (const SweepRow& r : t.rows) {
    Json row = {{"point", r.point->id}, {"index", r.point->index}, {"status", r.status}, {"pose", r.pose}};
    row["choices"] = Json::object();
    for (const auto& [name, label] : r.point->choices) row["choices"][name] = label;
    row["values"] = Json::object();
    for (const auto& [path, v] : r.point->values) row["values"][path] = v;
    for (size_t m = 0; m < t.metricNames.size(); ++m)
      row[t.metricNames[m]] = r.metrics[m] ? Json(*r.metrics[m]) : Json();
    j["rows"].push_back(std::move(row));
  }
  j["points"] = Json::array();
  for (const SweepPointStatus& p : t.points) {
    Json pj = {{"point", p.point->id}, {"index", p.point->index}, {"status", p.status}, {"seconds", p.seconds},
               {"references_cached", p.referencesCached}, {"references_rendered", p.referencesRendered}};
    if (!p.error.empty()) pj["error"] = p.error;
    j["points"].push_back(std::move(pj));
  }
  const int refs = t.cached + t.rendered;
  j["reference_cache"] = {{"cached", t.cached}, {"rendered", t.rendered},
                          {"hit_rate", refs > 0 ? Json(double(t.cached) / refs) : Json()}};
  j["noise_floor_de"] = t.noiseFloor ? Json(*t.noiseFloor) : Json();
  return j;
}

}  // namespace inim
