// A sweep's plan: expansion into points (grid, zip, alternatives), key paths into the display,
// its panel and MLA, the placement and the run's settings, stable ids, and every refusal before
// any work (unknown path, wrong type, empty axis, too many points).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "display/display.h"
#include "expect_input_error.h"
#include "scratch_dir.h"
#include "sweep/sweep_plan.h"
#include "sweep/sweep_point.h"

using namespace inim;

namespace {

SweepPlan planOf(const std::string& text) { return sweepPlanFromJson(parseJsonText(text, "plan.json"), "plan.json"); }

const char* kGapPitch = R"({"base": {"fig11": {"width": 64}},
  "axes": [{"path": "reconstruction_gap_mm", "values": [3.6, 4.0, 4.4]},
           {"path": "mla.pitch_mm", "range": {"from": 0.98, "to": 1.02, "count": 2}}]})";

}  // namespace

TEST(SweepPlan, AGridCrossesTheAxesFirstOutermost) {
  const std::vector<SweepPoint> points = expandSweep(planOf(kGapPitch));
  ASSERT_EQ(points.size(), 6u);
  const double gaps[] = {3.6, 3.6, 4.0, 4.0, 4.4, 4.4}, pitches[] = {0.98, 1.02, 0.98, 1.02, 0.98, 1.02};
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].index, int(i));
    EXPECT_EQ(points[i].values[0].second, gaps[i]);
    EXPECT_EQ(points[i].values[1].second, pitches[i]);  // the range's ends exactly
    EXPECT_EQ(points[i].config["display"]["reconstruction_gap_mm"].get<double>(), gaps[i]);
    // The MLA (a catalog name in the display file) is read in, so its keys are reachable.
    EXPECT_EQ(points[i].config["display"]["mla"]["pitch_mm"].get<double>(), pitches[i]);
    EXPECT_EQ(points[i].config["display"]["mla"]["focal_length_mm"].get<double>(), 3.3);
    EXPECT_EQ(points[i].config["fig11"]["width"].get<int>(), 64);
  }
}

TEST(SweepPlan, IdsFollowTheParametersOnly) {
  const std::vector<SweepPoint> a = expandSweep(planOf(kGapPitch));
  std::set<std::string> ids;
  for (const SweepPoint& p : a) {
    EXPECT_EQ(p.id.size(), 13u);
    EXPECT_EQ(p.id[0], 'p');
    ids.insert(p.id);
  }
  EXPECT_EQ(ids.size(), a.size());
  // Another base (the run's width) keeps the ids; the same parameters in another plan too.
  const std::vector<SweepPoint> b = expandSweep(planOf(R"({"base": {"fig11": {"width": 96}},
    "axes": [{"path": "reconstruction_gap_mm", "values": [4.4, 3.6]},
             {"path": "mla.pitch_mm", "values": [1.02]}]})"));
  EXPECT_EQ(b[0].id, a[5].id);
  EXPECT_EQ(b[1].id, a[1].id);
}

TEST(SweepPlan, ZipPairsTheAxesAndAlternativesMultiply) {
  const std::vector<SweepPoint> points = expandSweep(planOf(R"({"base": {},
    "axes": [{"path": "reconstruction_gap_mm", "values": [3.6, 4.4]},
             {"path": "placement.translate_mm[2]", "values": [-5, 5]}],
    "combine": "zip",
    "alternatives": [{"name": "subpixels", "options": [
        {"label": "stripe", "set": {"panel.subpixel_layout.order": "RGB"}},
        {"label": "bgr", "set": {"panel.subpixel_layout.order": "BGR"}}]},
      {"name": "mla", "options": [{"label": "real"}, {"label": "ideal", "set": {"fig11.mla": "ideal"}}]}]})"));
  ASSERT_EQ(points.size(), 8u);
  EXPECT_EQ(points[0].choices[0].second, "stripe");
  EXPECT_EQ(points[0].choices[1].second, "real");
  EXPECT_EQ(points[7].choices[0].second, "bgr");
  EXPECT_EQ(points[7].choices[1].second, "ideal");
  EXPECT_EQ(points[7].config["display"]["panel"]["subpixel_layout"]["order"], "BGR");
  EXPECT_EQ(points[7].config["fig11"]["mla"], "ideal");
  // Zipped: (3.6, -5) and (4.4, 5); the analytic scene's placement starts at the identity.
  EXPECT_EQ(points[1].values[0].second, 4.4);
  EXPECT_EQ(points[1].config["placement"]["translate_mm"], Json({0.0, 0.0, 5.0}));
  EXPECT_EQ(points[0].config["placement"]["translate_mm"], Json({0.0, 0.0, -5.0}));
}

TEST(SweepPlan, AWholeOtherDisplayIsAnAlternative) {
  const std::vector<SweepPoint> points = expandSweep(planOf(R"({"base": {},
    "alternatives": [{"name": "design", "options": [{"label": "flat"}, {"label": "barriers", "display": "barrier-mla"}]}]})"));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_TRUE(points[0].config["display"].contains("mla"));
  EXPECT_TRUE(points[1].config["display"].contains("stack"));
  EXPECT_NE(points[0].id, points[1].id);
}

TEST(SweepPlan, TheResolvedDisplayLoadsWithTheAxisValue) {
  ScratchDir scratch("sweep_plan_display");
  const std::vector<SweepPoint> points = expandSweep(planOf(kGapPitch));
  writeSweepPointFiles(scratch.dir().string(), points[3], "inim");
  const Display d = loadDisplay(sweepPointDir(scratch.dir().string(), points[3].id) + "/display.json");
  EXPECT_EQ(d.reconstructionGapMm, 4.0);
  EXPECT_EQ(d.mla.pitchMm, 1.02);
  EXPECT_EQ(d.panel.widthPx, loadDisplay(defaultDisplayPath()).panel.widthPx);
}

TEST(SweepPlan, BadPlansAreRefusedNamingTheAxisAndTheValue) {
  auto refused = [](const std::string& text, const std::string& key, const std::string& value) {
    const InputError e = expectInputError([&] { expandSweep(planOf(text)); });
    EXPECT_EQ(e.file(), "plan.json") << text;
    EXPECT_NE(e.key().find(key), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(value), std::string::npos) << e.what();
  };
  refused(R"({"base": {}, "axes": [{"path": "mla.pich_mm", "values": [1]}]})", "axes[0].path", "mla.pich_mm");
  refused(R"({"base": {}, "axes": [{"path": "gap_mm", "values": [1]}]})", "axes[0].path", "gap_mm");
  refused(R"({"base": {}, "axes": [{"path": "panel.eotf", "values": [1]}]})", "axes[0].path", "panel.eotf");
  refused(R"({"base": {}, "axes": [{"path": "ei_count[5]", "values": [1]}]})", "axes[0].path", "ei_count[5]");
  refused(R"({"base": {}, "axes": [{"path": "mla.pitch_mm", "values": []}]})", "values", "[]");
  refused(R"({"base": {}, "axes": [{"path": "mla.pitch_mm", "values": ["1.0"]}]})", "values", "1.0");
  refused(R"({"base": {}, "axes": [{"path": "mla.pitch_mm", "values": [1]}, {"path": "gap_mm", "values": [1, 2]}],
             "combine": "zip"})", "axes[1].values", "2 values");
  refused(R"({"base": {}, "alternatives": [{"name": "a", "options": [{"label": "x", "set": {"panel.eotf": 2}}]}]})",
          "panel.eotf", "panel.eotf");
  refused(R"({"base": {"fig11": {"widht": 64}}, "axes": [{"path": "mla.pitch_mm", "values": [1]}]})", "widht", "");
  refused(R"({"base": {}, "axes": [{"path": "mla.pitch_mm", "values": [1, 1]}]})", "axes", "points 0 and 1");
  refused(R"({"base": {}, "axes": [{"path": "mla.pitch_mm", "values": [1]}], "axis": []})", "axis", "");
  // More points than allowed: refused by count, before any point is built.
  const InputError e = expectInputError([&] {
    expandSweep(planOf(R"({"base": {}, "axes": [{"path": "mla.pitch_mm", "range": {"from": 0.9, "to": 1.1, "count": 100}},
                                            {"path": "reconstruction_gap_mm", "range": {"from": 3, "to": 5, "count": 101}}]})"));
  });
  EXPECT_NE(std::string(e.what()).find("10100 points"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("10000"), std::string::npos) << e.what();
  EXPECT_EQ(expandSweep(planOf(kGapPitch), 6).size(), 6u);
  expectInputError([&] { expandSweep(planOf(kGapPitch), 5); });
}

TEST(SweepPlan, KeyPathsReachNestedValuesAndArrays) {
  Json doc = parseJsonText(R"({"a": {"b": [1, {"c": 2}]}, "s": "x"})", "doc");
  setKeyPath(doc, "a.b[1].c", 5, "f", "k", true);
  setKeyPath(doc, "a.b[0]", 7.5, "f", "k", true);
  EXPECT_EQ(doc["a"]["b"][1]["c"], 5);
  EXPECT_EQ(doc["a"]["b"][0], 7.5);
  EXPECT_EQ(findKeyPath(doc, "a.b[2]"), nullptr);
  EXPECT_EQ(findKeyPath(doc, "a..b"), nullptr);
  EXPECT_EQ(findKeyPath(doc, "a.b[x]"), nullptr);
  EXPECT_EQ(findKeyPath(doc, ""), nullptr);
  expectInputError([&] { setKeyPath(doc, "s", 1, "f", "k", true); });
  setKeyPath(doc, "s", "y", "f", "k", false);
  EXPECT_EQ(doc["s"], "y");
}

TEST(SweepPlan, OnlyPlacementCameraAndRenderKeysChangeTheReferences) {
  for (const char* p : {"placement.translate_mm[2]", "placement.scale[0]", "fig11.distance_mm", "fig11.width",
                        "fig11.reference_spp", "fig11.seed", "fig11.angle"})
    EXPECT_TRUE(keyPathChangesReferences(p)) << p;
  for (const char* p : {"mla.pitch_mm", "reconstruction_gap_mm", "panel.pixel_pitch_mm", "fig11.spp", "fig11.eia_spp",
                        "fig11.aperture_grid", "stack.layers[1].pitch_mm"})
    EXPECT_FALSE(keyPathChangesReferences(p)) << p;
}

TEST(SweepPlan, ThePlanRoundTripsThroughItsJson) {
  const SweepPlan plan = planOf(kGapPitch);
  const SweepPlan again = sweepPlanFromJson(sweepPlanJson(plan), "plan.json");
  const std::vector<SweepPoint> a = expandSweep(plan), b = expandSweep(again);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].config, b[i].config);
  }
  // References are rendered at every pixel by default in a sweep: shared by display changes.
  EXPECT_EQ(a[0].config["fig11"]["reference_every_pixel"], true);
}
