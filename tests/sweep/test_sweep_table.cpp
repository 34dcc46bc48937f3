// A sweep's table and report from its points' results: a point counts only when its result is
// complete (checked against its point.json and its files), the best point, the sensitivity
// (slope and the 1-CIEDE2000 tolerance along each axis, on an analytic metric), and the
// noise-floor marks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/content_hash.h"
#include "scratch_dir.h"
#include "sweep/sweep_plan.h"
#include "sweep/sweep_point.h"
#include "sweep/sweep_report.h"
#include "sweep/sweep_table.h"

using namespace inim;
namespace fs = std::filesystem;

namespace {

const char* kPlan = R"({"base": {},
  "axes": [{"path": "reconstruction_gap_mm", "values": [3.0, 3.5, 4.0, 4.5, 5.0]},
           {"path": "mla.pitch_mm", "values": [0.98, 1.0, 1.02]}]})";

// The metric of the fake results: a paraboloid with its minimum 2 at gap 4, pitch 1.0.
double paraboloid(double gap, double pitch) { return 2.0 + 3.0 * (gap - 4.0) * (gap - 4.0) + 2e4 * (pitch - 1.0) * (pitch - 1.0); }

// A result.json as runSweepPoint writes it, for one pose, with one hashed file.
void writeResult(const std::string& dir, const SweepPoint& p, double de, double noiseFloor) {
  writeSweepPointFiles(dir, p, "inim");
  const fs::path pd = sweepPointDir(dir, p.id);
  fs::create_directories(pd / "fig11");
  std::ofstream(pd / "fig11/metrics.json") << "{\"de\": " << de << "}\n";
  Json pose = {{"pose", "centre"}, {"psnr_db", 30 - de}, {"ssim", 0.9}, {"de_mean", de}, {"de_p95", 2 * de},
               {"de_max", 4 * de}, {"pixels", 100}, {"de_mean_band_limited", de}, {"noise_floor_de", noiseFloor},
               {"budget", {{{"rung", "ideal"}, {"de_mean", de / 2}}, {{"rung", "+subpixels"}, {"de_mean", nullptr}}}}};
  Json r = {{"format", "inim sweep point 1"}, {"id", p.id}, {"status", "ok"},
            {"point_sha256", fileSha256((pd / "point.json").string())},
            {"files", {{"fig11/metrics.json", fileSha256((pd / "fig11/metrics.json").string())}}},
            {"poses", {pose}}, {"references", {{"cached", 1}, {"rendered", 0}}}, {"seconds", 1.0}};
  std::ofstream(pd / "result.json") << r.dump(2);
}

struct FakeSweep {
  ScratchDir scratch{"sweep_table"};
  std::string dir = scratch.dir().string();
  SweepPlan plan = sweepPlanFromJson(parseJsonText(kPlan, "plan.json"), "plan.json");
  std::vector<SweepPoint> points = expandSweep(plan);
  explicit FakeSweep(double noiseFloor = 0.5) {
    for (const SweepPoint& p : points) writeResult(dir, p, paraboloid(p.values[0].second, p.values[1].second), noiseFloor);
  }
};

}  // namespace

TEST(SweepTable, OnlyCompleteResultsCount) {
  FakeSweep s;
  const SweepPoint& a = s.points[0];
  const SweepPoint& b = s.points[1];
  const SweepPoint& c = s.points[2];
  ASSERT_FALSE(completeSweepResult(s.dir, a.id).is_null());
  // A file it names changed: not complete.
  std::ofstream(fs::path(sweepPointDir(s.dir, a.id)) / "fig11/metrics.json") << "{}";
  EXPECT_TRUE(completeSweepResult(s.dir, a.id).is_null());
  // Its point.json changed (another plan's point in this folder): not complete.
  std::ofstream(fs::path(sweepPointDir(s.dir, b.id)) / "point.json", std::ios::app) << " ";
  EXPECT_TRUE(completeSweepResult(s.dir, b.id).is_null());
  // Recorded as failed: listed with its error, without metrics.
  recordSweepFailure(s.dir, c.id, "display: key 'mla.pitch_mm': value -1");
  const SweepTable t = collectSweepTable(s.dir, s.points);
  EXPECT_EQ(t.points[0].status, "missing");
  EXPECT_EQ(t.points[1].status, "missing");
  EXPECT_EQ(t.points[2].status, "failed");
  EXPECT_EQ(t.points[2].error, "display: key 'mla.pitch_mm': value -1");
  EXPECT_EQ(t.points[3].status, "ok");
  EXPECT_EQ(t.rows.size(), s.points.size());  // one pose per point, one row per point without one
  EXPECT_FALSE(t.rows[2].metrics[t.metric("de_mean")]);
}

TEST(SweepTable, RowsCarryTheParametersAndTheBudget) {
  FakeSweep s;
  const SweepTable t = collectSweepTable(s.dir, s.points);
  ASSERT_EQ(t.rows.size(), 15u);
  EXPECT_EQ(t.firstPose, "centre");
  ASSERT_GE(t.metric("budget_ideal"), 0);
  ASSERT_GE(t.metric("budget_+subpixels"), 0);
  const SweepRow& r = t.rows[5];  // gap 3.5, pitch 1.02
  EXPECT_DOUBLE_EQ(*r.metrics[t.metric("de_mean")], paraboloid(3.5, 1.02));
  EXPECT_DOUBLE_EQ(*r.metrics[t.metric("budget_ideal")], paraboloid(3.5, 1.02) / 2);
  EXPECT_FALSE(r.metrics[t.metric("budget_+subpixels")]);  // a skipped rung
  ASSERT_TRUE(t.noiseFloor);
  EXPECT_DOUBLE_EQ(*t.noiseFloor, 0.5);
  EXPECT_EQ(t.cached, 15);
  const std::string csv = sweepTableCsv(t, s.points);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "point,index,reconstruction_gap_mm,mla.pitch_mm,status,pose,psnr_db,ssim,de_mean,de_p95,de_max,"
            "de_mean_band_limited,noise_floor_de,budget_ideal,budget_+subpixels");
  // No times or cache counts in the CSV: a local and a cluster run give the same bytes.
  EXPECT_EQ(csv.find("seconds"), std::string::npos);
}

TEST(SweepReport, SensitivityAtTheBestPointMatchesTheParaboloid) {
  FakeSweep s;
  const SweepTable t = collectSweepTable(s.dir, s.points);
  const SweepPoint* best = bestSweepPoint(t, s.points);
  ASSERT_NE(best, nullptr);
  EXPECT_EQ(best->values[0].second, 4.0);
  EXPECT_EQ(best->values[1].second, 1.0);
  const std::vector<AxisSensitivity> sens = sweepSensitivity(t, s.points, s.plan);
  ASSERT_EQ(sens.size(), 2u);
  // Central differences of a paraboloid at its vertex are 0.
  EXPECT_TRUE(sens[0].slopeKnown);
  EXPECT_NEAR(sens[0].slope, 0.0, 1e-9);
  EXPECT_NEAR(sens[1].slope, 0.0, 1e-6);
  // Gap: 3 (g - 4)^2 <= 1 for |g - 4| <= 0.577: of the sweep's values, 3.5 to 4.5 (+0.75 each).
  EXPECT_EQ(sens[0].lo, 3.5);
  EXPECT_EQ(sens[0].hi, 4.5);
  EXPECT_FALSE(sens[0].loAtEnd);
  EXPECT_FALSE(sens[0].hiAtEnd);
  // Pitch: 2e4 (p - 1)^2 = 8 at +-0.02: only the best point's own value.
  EXPECT_EQ(sens[1].lo, 1.0);
  EXPECT_EQ(sens[1].hi, 1.0);
}

TEST(SweepReport, TheReportMarksDifferencesBelowTheNoiseFloor) {
  FakeSweep s(0.8);
  const SweepTable t = collectSweepTable(s.dir, s.points);
  writeSweepReport(s.dir, s.plan, s.points, t, "inim");
  std::ifstream in(fs::path(s.dir) / "report.md");
  const std::string report((std::istreambuf_iterator<char>(in)), {});
  // Gap 3.5 or 4.5 at pitch 1.0: +0.75 < 0.8, not significant; pitch 0.98: +8, significant.
  EXPECT_NE(report.find("+0.750 (not significant)"), std::string::npos) << report;
  EXPECT_NE(report.find("+8.000 |"), std::string::npos) << report;
  EXPECT_NE(report.find("Noise floor of the references (CIEDE2000 between two seeds at centre): 0.80"),
            std::string::npos);
  EXPECT_NE(report.find("hit rate 100 %"), std::string::npos);
  for (const char* f : {"results.csv", "results.json", "plots/heatmap.png", "plots/de_mean_vs_mla_pitch_mm.png"})
    EXPECT_TRUE(fs::exists(fs::path(s.dir) / f)) << f;
}
