// The placement page's state, run file and output names (src/place/place_state.h, place_jobs.h).
#include <gtest/gtest.h>

#include "core/json_config.h"
#include "expect_input_error.h"
#include "fixtures.h"
#include "place/place_jobs.h"
#include "place/place_state.h"
#include "runs/run_file.h"

using namespace inim;

namespace {

PlaceState someState() {
  PlaceState s;
  s.display = "/data/d.json";
  s.placement.scale = Vec3d(2.0);
  s.placement.rotateDeg = Vec3d(10.0, -20.0, 0.1);
  s.placement.translateMm = Vec3d(0.1, 0.2, 1.0 / 3.0);
  s.vcpMm = 80.0;
  return s;
}

PlaceState patched(const PlaceState& s, const std::string& body) {
  return applyStatePatch(s, parseJsonText(body, "request body"), {"/data/d.json", "/data/e.json"});
}

}  // namespace

TEST(PlaceState, APartialPatchChangesOnlyItsKeys) {
  const PlaceState s = someState();
  const PlaceState t = patched(s, R"({"placement": {"translate_mm": [1, 2, 3]}, "vcp_mm": -5, "layout": "toed-in"})");
  EXPECT_EQ(t.placement.translateMm, Vec3d(1, 2, 3));
  EXPECT_EQ(t.placement.rotateDeg, s.placement.rotateDeg);
  EXPECT_EQ(t.placement.scale, s.placement.scale);
  EXPECT_EQ(t.vcpMm, -5.0);
  EXPECT_EQ(t.layout, "toed-in");
  EXPECT_EQ(patched(s, R"({"placement": {"scale": 3}})").placement.scale, Vec3d(3.0));
  EXPECT_EQ(patched(s, R"({"display": "/data/e.json", "revision": 7})").display, "/data/e.json");
}

TEST(PlaceState, BadPatchesNameTheKeyAndValue) {
  const PlaceState s = someState();
  struct Case { const char* body; const char* key; };
  for (const Case c : {Case{R"({"vcp_mm": 20000})", "vcp_mm"}, Case{R"({"vcp_mm": "far"})", "vcp_mm"},
                       Case{R"({"placement": {"scale": 0}})", "placement.scale"},
                       Case{R"({"placement": {"scale": [1, 1e7, 1]}})", "placement.scale"},
                       Case{R"({"placement": {"rotate_deg": [0, 400, 0]}})", "placement.rotate_deg"},
                       Case{R"({"placement": {"translate_mm": [0, 0]}})", "placement.translate_mm"},
                       Case{R"({"placement": {"shear": 1}})", "placement.shear"},
                       Case{R"({"layout": "lens-grid"})", "layout"},
                       Case{R"({"viewing_distance_mm": 1})", "viewing_distance_mm"},
                       Case{R"({"display": "/etc/passwd"})", "display"},
                       Case{R"({"vpc_mm": 1})", "vpc_mm"}}) {
    const InputError e = expectInputError([&] { patched(s, c.body); });
    EXPECT_NE(std::string(e.what()).find(c.key), std::string::npos) << c.body << ": " << e.what();
  }
  // Not JSON, a number a double cannot hold, and not an object.
  for (const char* body : {"{\"vcp_mm\": ", "{\"vcp_mm\": 1e400}", "[1, 2]", "{\"vcp_mm\": NaN}"})
    expectInputError([&] { patched(s, body); });
}

TEST(PlaceState, TheRunFileReadsBackAsTheState) {
  const PlaceState s = someState();
  const std::string file = fixtures::scratchFile("place-run.json", runFileJson(s, "/data/scene.json").dump(2));
  const RunFile r = loadRunFile(file);
  ASSERT_TRUE(r.placement);
  EXPECT_EQ(r.placement->scale, s.placement.scale);  // exact: the JSON keeps every bit
  EXPECT_EQ(r.placement->rotateDeg, s.placement.rotateDeg);
  EXPECT_EQ(r.placement->translateMm, s.placement.translateMm);
  EXPECT_EQ(*r.vcpMm, s.vcpMm);
  EXPECT_EQ(*r.layout, s.layout);
  EXPECT_EQ(*r.viewingDistanceMm, s.viewingDistanceMm);
  EXPECT_EQ(*r.display, s.display);
  EXPECT_EQ(*r.scene, "/data/scene.json");
}

TEST(PlaceJobs, OutputNamesCannotLeaveTheFolder) {
  for (const char* bad : {"", "..", "../x", "a/b", "/etc/passwd", ".hidden", "a\\b", "a b", "x\n"})
    expectInputError([&] { sanitizeOutputName(bad); });
  expectInputError([&] { sanitizeOutputName(std::string(101, 'a')); });
  EXPECT_EQ(sanitizeOutputName("run-1_b.v2"), "run-1_b.v2");
  EXPECT_EQ(sanitizeOutputName(std::string(100, 'a')), std::string(100, 'a'));
}
