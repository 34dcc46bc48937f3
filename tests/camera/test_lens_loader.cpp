// Lens files: the pbrt-v4 format and the JSON form, the thickness conventions, orientation,
// glass forms, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "camera/lens_analysis.h"
#include "camera/lens_loader.h"
#include "camera_test_util.h"
#include "core/output_file.h"

using namespace inim;
using inim::test::scratchFile;

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The rows of a pbrt file (numbers only).
std::vector<std::array<double, 4>> pbrtRows(const std::string& text) {
  std::vector<std::array<double, 4>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream l(line);
    std::array<double, 4> r{};
    if (l >> r[0] >> r[1] >> r[2] >> r[3]) rows.push_back(r);
  }
  return rows;
}

std::string rowsText(const std::vector<std::array<double, 4>>& rows, const std::string& header) {
  std::ostringstream o;
  o << header;
  o.precision(17);
  for (const auto& r : rows) o << r[0] << " " << r[1] << " " << r[2] << " " << r[3] << "\n";
  return o.str();
}

// The JSON form of a pbrt table (constant indices, object-first).
Json jsonFromRows(const std::vector<std::array<double, 4>>& rows) {
  Json j;
  j["name"] = "converted";
  j["surfaces"] = Json::array();
  for (const auto& r : rows) {
    Json s;
    if (r[0] == 0.0 && r[2] == 0.0) {
      s["stop"] = true;
    } else {
      s["radius_mm"] = r[0];
      if (r[2] > 1.0) s["glass"] = {{"n", r[2]}};
    }
    s["thickness_mm"] = r[1];
    s["aperture_mm"] = r[3];
    j["surfaces"].push_back(s);
  }
  return j;
}

}  // namespace

TEST(LensLoader, ShippedLensEflsByRealRayTracing) {
  // docs/design.md: paraxial EFL 50.36 mm and 249.57 mm; a real near-axis trace must agree.
  LensInfo dg = analyzeLens(loadLens("dgauss.50mm"));
  LensInfo tele = analyzeLens(loadLens("telephoto.250mm"));
  EXPECT_NEAR(dg.eflMm, 50.36, 0.005 * 50.36);
  EXPECT_NEAR(tele.eflMm, 249.57, 0.005 * 249.57);
  // They agree to the quoted digits.
  EXPECT_NEAR(dg.eflMm, 50.36, 0.005);
  EXPECT_NEAR(tele.eflMm, 249.57, 0.005);
  RecordProperty("dgauss_efl_mm", std::to_string(dg.eflMm));
  RecordProperty("telephoto_efl_mm", std::to_string(tele.eflMm));
  std::printf("EFL dgauss.50mm %.4f mm, telephoto.250mm %.4f mm; dgauss f/%.3f, BFL %.4f mm\n", dg.eflMm,
              tele.eflMm, dg.fNumber, dg.bflMm);
}

TEST(LensLoader, BeforeConventionReproducesAfter) {
  const std::string path = dataPath("optics/lenses/dgauss.50mm.dat");
  auto rows = pbrtRows(readText(path));
  // Convert: thickness before row i = thickness after row i-1; the first has no previous.
  auto before = rows;
  for (size_t i = 0; i < rows.size(); ++i) before[i][1] = i == 0 ? 0.0 : rows[i - 1][1];
  std::string f = scratchFile("dgauss_before.dat", rowsText(before, "# dgauss, before\n# thickness_convention: before\n"));
  LensSystem a = loadLens(path), b = loadLens(f);
  ASSERT_EQ(a.surfaceCount(), b.surfaceCount());
  for (int i = 0; i < a.surfaceCount(); ++i) EXPECT_DOUBLE_EQ(a.vertexZ(i), b.vertexZ(i));
  EXPECT_DOUBLE_EQ(analyzeLens(a).eflMm, analyzeLens(b).eflMm);
  EXPECT_DOUBLE_EQ(analyzeLens(a).bflMm, analyzeLens(b).bflMm);
  // The same through the loader option (the file without the directive).
  std::string g = scratchFile("dgauss_before_nodirective.dat", rowsText(before, "# dgauss\n"));
  LensLoadOptions opt;
  opt.thicknessConvention = ThicknessConvention::Before;
  LensSystem c = loadLens(g, opt);
  EXPECT_DOUBLE_EQ(analyzeLens(a).eflMm, analyzeLens(c).eflMm);
  // And read as "after" it is a different (wrong) lens, or an invalid one.
  try {
    LensSystem wrong = loadLens(g);
    EXPECT_GT(std::abs(analyzeLens(wrong).eflMm - analyzeLens(a).eflMm), 0.1);
  } catch (const InputError&) {
  }
  // JSON with "thickness_convention": "before".
  Json j = jsonFromRows(before);
  j["thickness_convention"] = "before";
  LensSystem d = parseLensJson(JsonObject(j, "before.json", ""));
  EXPECT_NEAR(analyzeLens(d).eflMm, analyzeLens(a).eflMm, 1e-6);
}

TEST(LensLoader, JsonFormMatchesPbrtAndImageFirstOrientation) {
  const std::string path = dataPath("optics/lenses/dgauss.50mm.dat");
  auto rows = pbrtRows(readText(path));
  LensSystem a = loadLens(path);
  Json j = jsonFromRows(rows);
  LensSystem b = parseLensJson(JsonObject(j, "dgauss.json", ""));
  const LensInfo ia = analyzeLens(a), ib = analyzeLens(b);
  EXPECT_NEAR(ib.eflMm, ia.eflMm, 1e-6);
  EXPECT_NEAR(ib.bflMm, ia.bflMm, 1e-6);
  // Listed from the image side: each row's glass and thickness describe the space toward the
  // object; radii keep their sign convention (centre toward +z of the listing direction).
  Json r;
  r["orientation"] = "image-first";
  r["surfaces"] = Json::array();
  const size_t n = rows.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t i = n - 1 - k;  // object-first index
    Json s;
    if (rows[i][0] == 0.0 && rows[i][2] == 0.0) s["stop"] = true;
    else s["radius_mm"] = -rows[i][0];
    s["aperture_mm"] = rows[i][3];
    if (i > 0) {
      s["thickness_mm"] = rows[i - 1][1];
      if (rows[i - 1][2] > 1.0) s["glass"] = {{"n", rows[i - 1][2]}};
    }
    r["surfaces"].push_back(s);
  }
  LensSystem c = parseLensJson(JsonObject(r, "reversed.json", ""));
  const LensInfo ic = analyzeLens(c);
  EXPECT_NEAR(ic.eflMm, ia.eflMm, 1e-6);
  EXPECT_NEAR(ic.bflMm, ia.bflMm, 1e-6);
  EXPECT_NEAR(ic.entrancePupil.positionMm, ia.entrancePupil.positionMm, 1e-6);
  // Scale multiplies every length: EFL scales.
  Json s = j;
  s["scale"] = 0.5;
  EXPECT_NEAR(analyzeLens(parseLensJson(JsonObject(s, "half.json", ""))).eflMm, 0.5 * ia.eflMm, 1e-6);
  // lensToPbrtText round trip.
  std::string rt = scratchFile("roundtrip.dat", lensToPbrtText(b));
  EXPECT_NEAR(analyzeLens(loadLens(rt)).eflMm, ia.eflMm, 1e-6);
}

TEST(LensLoader, GlassByCatalogSellmeierAndAbbe) {
  auto lensWith = [](const Json& glass) {
    Json j = {{"surfaces", Json::array({Json{{"stop", true}, {"aperture_mm", 10.0}},
                                        Json{{"radius_mm", 40.0}, {"thickness_mm", 4.0}, {"aperture_mm", 10.0}, {"glass", glass}},
                                        Json{{"radius_mm", -40.0}, {"aperture_mm", 10.0}}})}};
    return parseLensJson(JsonObject(j, "glass.json", ""));
  };
  LensSystem cat = lensWith("N-BK7");
  LensSystem sell = lensWith(Json{{"sellmeier_b", {1.03961212, 0.231792344, 1.01046945}},
                                  {"sellmeier_c", {0.00600069867, 0.0200179144, 103.560653}}});
  LensSystem abbe = lensWith(Json{{"nd", 1.5168}, {"vd", 64.17}});
  for (double l : {450.0, 587.56, 650.0}) {
    EXPECT_NEAR(cat.indexAfter(1, l), sell.indexAfter(1, l), 1e-6);
    EXPECT_NEAR(abbe.indexAfter(1, l), cat.indexAfter(1, l), 5e-4);  // two-term Cauchy vs Sellmeier
  }
  EXPECT_NEAR(abbe.indexAfter(1, 587.56), 1.5168, 1e-6);
  EXPECT_TRUE(cat.isDispersive());
  // Abbe number from the traced indices: (n_d - 1) / (n_F - n_C) = 64.17.
  EXPECT_NEAR((abbe.indexAfter(1, 587.56) - 1.0) / (abbe.indexAfter(1, 486.13) - abbe.indexAfter(1, 656.27)), 64.17, 0.01);
  // pbrt files: no dispersion by default, Cauchy with a V_d on request.
  EXPECT_FALSE(loadLens("dgauss.50mm").isDispersive());
  LensLoadOptions o;
  o.pbrtDispersion = PbrtDispersion::Abbe;
  o.abbeNumber = 40.0;
  LensSystem d = loadLens("dgauss.50mm", o);
  EXPECT_TRUE(d.isDispersive());
  EXPECT_NEAR(analyzeLens(d).eflMm, analyzeLens(loadLens("dgauss.50mm")).eflMm, 1e-4);  // same at n_d
  EXPECT_NEAR((d.indexAfter(0, 587.56) - 1.0) / (d.indexAfter(0, 486.13) - d.indexAfter(0, 656.27)), 40.0, 0.01);
}

TEST(LensLoader, EdmundStandInIsA12mmAchromat) {
  LensSystem lens = loadLens("edmund-85-351-standin");
  LensInfo d = analyzeLens(lens, 587.56);
  EXPECT_NEAR(d.eflMm, 12.0, 0.012);
  EXPECT_TRUE(lens.isDispersive());
  // Achromatised: F and C focus within 1 um; the d focus within 2 um of them.
  const double bF = analyzeLens(lens, 486.13).bflMm, bC = analyzeLens(lens, 656.27).bflMm;
  EXPECT_NEAR(bF, bC, 1e-3);
  EXPECT_NEAR(d.bflMm, 0.5 * (bF + bC), 2e-3);
  std::printf("stand-in: EFL %.4f mm, f/%.3f, BFL %.4f mm, F-C focus %.2f um\n", d.eflMm, d.fNumber, d.bflMm,
              1e3 * (bF - bC));
}

TEST(LensLoader, MalformedRowsNameFileAndLine) {
  std::string f = scratchFile("bad_row.dat", "# bad\n29.475 3.76 1.67 25.2\n84.83 0.12 1\n0 4 0 17\n-40 0 1 20\n");
  InputError e = expectInputError([&] { loadLens(f); });
  EXPECT_EQ(e.file(), f);
  EXPECT_NE(e.key().find("line 3"), std::string::npos) << e.what();
  f = scratchFile("bad_num.dat", "# bad\n29.475 3.76 1.67 25.2\n84.83 abc 1 25\n");
  e = expectInputError([&] { loadLens(f); });
  EXPECT_NE(e.key().find("line 3"), std::string::npos) << e.what();
  EXPECT_NE(e.value().find("abc"), std::string::npos);
  f = scratchFile("bad_index.dat", "# bad\n29.475 3.76 0.5 25.2\n0 4 0 17\n-40 0 1 20\n");
  e = expectInputError([&] { loadLens(f); });
  EXPECT_NE(e.key().find("index"), std::string::npos) << e.what();
  f = scratchFile("bad_directive.dat", "# thickness_convention: sideways\n0 4 0 17\n");
  e = expectInputError([&] { loadLens(f); });
  EXPECT_NE(e.key().find("thickness_convention"), std::string::npos) << e.what();
  e = expectInputError([&] { loadLens("/nonexistent/lens.dat"); });
  EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  e = expectInputError([&] { loadLens("no-such-lens"); });
  EXPECT_NE(e.expected().find("dgauss.50mm"), std::string::npos) << e.what();  // lists the known names
}

TEST(LensLoader, InconsistentAperturesAndGeometry) {
  auto rows = pbrtRows(readText(dataPath("optics/lenses/dgauss.50mm.dat")));
  auto check = [&](auto modify, const std::string& keyPart, const std::string& name) {
    auto r = rows;
    modify(r);
    std::string f = scratchFile(name + ".dat", rowsText(r, "# " + name + "\n"));
    InputError e = expectInputError([&] { loadLens(f); });
    EXPECT_EQ(e.file(), f);
    EXPECT_NE(e.key().find(keyPart), std::string::npos) << name << ": " << e.what();
    return e;
  };
  // The stop (row 6, line 7) much larger than its neighbours: the axial beam cannot fill it.
  InputError e = check([](auto& r) { r[5][3] = 40.0; }, "line 7", "stop_too_big");
  EXPECT_NE(e.key().find("aperture"), std::string::npos);
  EXPECT_NE(e.expected().find("stop"), std::string::npos);
  check([](auto& r) { r[2][3] = 0.0; }, "line 4", "zero_aperture");
  check([](auto& r) { r[2][3] = -5.0; }, "line 4", "negative_aperture");
  // |R| < aperture / 2: surface 5 (R 12.75) with a 30 mm aperture.
  e = check([](auto& r) { r[4][3] = 30.0; }, "line 6", "radius_too_small");
  EXPECT_NE(e.expected().find("radius"), std::string::npos);
  check([](auto& r) { r[1][1] = -1.0; }, "line 3", "negative_thickness");
  check([](auto& r) { r[0][1] = 0.0; }, "line 2", "zero_glass_thickness");
  check([](auto& r) { r[5][2] = 1.0; }, "stop", "no_stop");
  // A ring of apertures that blocks the axis? A tiny element aperture makes the stop unfillable.
  check([](auto& r) { r[1][3] = 1.0; }, "line 7", "tiny_element");
}

TEST(LensLoader, JsonErrorsNameKeys) {
  auto parse = [](const Json& j) { return parseLensJson(JsonObject(j, "lens.json", "")); };
  Json good = {{"surfaces", Json::array({Json{{"stop", true}, {"aperture_mm", 10.0}},
                                         Json{{"radius_mm", 40.0}, {"thickness_mm", 4.0}, {"aperture_mm", 10.0}, {"glass", "N-BK7"}},
                                         Json{{"radius_mm", -40.0}, {"aperture_mm", 10.0}}})}};
  EXPECT_NO_THROW(parse(good));
  Json j = good;
  j["surfaces"][1]["glass"] = "unobtainium";
  InputError e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.file(), "lens.json");
  EXPECT_EQ(e.key(), "surfaces[1].glass");
  EXPECT_NE(e.expected().find("N-BK7"), std::string::npos);
  j = good;
  j["surfaces"][1]["radius_mm"] = 4.0;  // smaller than the 5 mm semi-aperture
  e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.key(), "surfaces[1].aperture_mm");
  j = good;
  j["surfaces"][2]["aperture_mm"] = 0.0;
  e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.key(), "surfaces[2].aperture_mm");
  j = good;
  j["surfaces"][1]["thikness_mm"] = 4.0;  // misspelt
  e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.key(), "surfaces[1].thikness_mm");
  j = good;
  j["surfaces"][1]["glass"] = {{"nd", 1.5}};  // vd missing
  e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.key(), "surfaces[1].glass.vd");
  j = good;
  j["orientation"] = "sideways";
  e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.key(), "orientation");
  j = good;
  j["surfaces"][1]["conic"] = -3.0;  // hyperboloid fine; an oblate ellipsoid too strong is not
  EXPECT_NO_THROW(parse(j));
  j["surfaces"][1]["conic"] = 70.0;  // 1 - (1+k) c^2 r^2 < 0 at the edge
  e = expectInputError([&] { parse(j); });
  EXPECT_EQ(e.key(), "surfaces[1].aperture_mm");
}
