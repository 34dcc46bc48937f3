// Geometry of the orthoscopic synthesis, against pinhole geometry: point images land on the
// predicted EI pixels (real and virtual), occlusion is the viewer's, the VCP clips, toed-in
// EI pitch, placements.
#include <gtest/gtest.h>

#include <filesystem>

#include "rays/pinhole_rays.h"
#include "synth_test_util.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/orthoscopic.h"

using namespace inim;
using namespace synth_test;

TEST(Orthoscopic, QueryRayStartsOnTheVcpAndPointsIntoTheScene) {
  OrthoscopicQuery oq(Transform(), 40.0);
  Vec3d d = glm::normalize(Vec3d(0.1, -0.05, 1.0));
  auto q = oq.make({1.0, 2.0, 0.0}, d, 7, 3);
  EXPECT_NEAR(q.vcpPoint.z, 40.0, 1e-12);
  // On the display ray: o = pinhole + d * D / d.z.
  EXPECT_NEAR(q.vcpPoint.x, 1.0 + d.x * 40.0 / d.z, 1e-12);
  EXPECT_NEAR(q.ray.d.z, -d.z, 1e-6);
  EXPECT_EQ(q.ray.tNear, 0.0f);
  EXPECT_EQ(q.ray.id, 7u);
  EXPECT_EQ(q.ray.sample, 3u);
  // The pinhole is at display distance D / d.z from the VCP.
  EXPECT_NEAR(OrthoscopicQuery::hitZ(q, 40.0 / d.z), 0.0, 1e-9);
}

TEST(Orthoscopic, PlacementScalesFieldDistances) {
  // Field scaled by 4 mm/unit and moved: the field ray has a unit direction, and a field
  // distance converts back to display mm by displayPerField.
  Placement pl;
  pl.scale = Vec3d(4.0);
  pl.translateMm = {1.0, -2.0, -5.0};
  pl.rotateDeg = {10.0, 20.0, 30.0};
  Transform T = pl.toDisplay();
  OrthoscopicQuery oq(T, 30.0);
  Vec3d d = glm::normalize(Vec3d(-0.2, 0.1, 1.0));
  auto q = oq.make({0.5, 0.5, 0.0}, d, 0, 0);
  EXPECT_NEAR(glm::length(Vec3d(q.ray.d)), 1.0, 1e-6);
  EXPECT_NEAR(q.displayPerField, 4.0, 1e-9);
  // A point 10 field units along the field ray is 40 mm along the display ray.
  Point3d pf = Point3d(q.ray.o) + 10.0 * Point3d(q.ray.d);
  Point3d pd = T.point(pf);
  Point3d expected = OrthoscopicQuery::hitPoint(q, 10.0);
  EXPECT_NEAR(glm::length(pd - expected), 0.0, 1e-4);
  EXPECT_NEAR(expected.z, 30.0 - 40.0 * d.z, 1e-9);
}

TEST(Orthoscopic, SingularPlacementIsAnInputError) {
  Placement pl;
  pl.scale = {1.0, 0.0, 1.0};
  InputError e = expectInputError([&] { (void)pl.toDisplay(); });
  EXPECT_EQ(e.key(), "scale");
  EXPECT_NE(std::string(e.what()).find("1, 0, 1"), std::string::npos) << e.what();
  pl.scale = Vec3d(0.0);
  expectInputError([&] { (void)pl.toDisplay(); });

  // Through synthesis too, and from a run file (naming the file and key).
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 5});
  EiLayout L = computeLayout(disp);
  MockField f({}, FieldEncoding::RGB);
  SynthesisSettings s = quietSettings(50.0);
  s.placement.scale = {2.0, 2.0, 0.0};
  expectInputError([&] { (void)synthesizeEia(L, disp.panel, f, s); });

}

TEST(Orthoscopic, ParseVec3) {
  EXPECT_EQ(parseVec3("1,2.5,-3", "--translate-mm"), Vec3d(1, 2.5, -3));
  EXPECT_EQ(parseVec3("2", "--scale", true), Vec3d(2.0));
  EXPECT_EQ(expectInputError([] { (void)parseVec3("1,2", "--rotate-deg"); }).key(), "--rotate-deg");
  expectInputError([] { (void)parseVec3("1,2,x", "--rotate-deg"); });
  expectInputError([] { (void)parseVec3("2", "--translate-mm"); });
  expectInputError([] { (void)parseVec3("1,2,3,", "--translate-mm"); });
}

// A small bright emitter at depth z: in every EI that sees it, the brightest pixel is the one
// pinhole geometry predicts. Real (z > 0) and virtual (z < 0), on the parallel and the
// lens-grid layouts.
class PointImage : public ::testing::TestWithParam<std::tuple<double, EiLayoutKind>> {};

TEST_P(PointImage, LandsOnPredictedPixel) {
  auto [z, kind] = GetParam();
  Display disp = squareDisplay(
      {.cols = 11, .rows = 9, .eiPx = 9, .layout = kind, .lensPitchMm = kind == EiLayoutKind::LensGrid ? 0.95 : 0.0});
  const SynthesisResult r = expectPointImageOnPredictedPixels(computeLayout(disp), disp.panel, z);
  EXPECT_EQ(r.stats.gamut.outOfGamut, 0u);
}

INSTANTIATE_TEST_SUITE_P(RealAndVirtual, PointImage,
                         ::testing::Values(std::tuple{12.0, EiLayoutKind::Parallel},
                                           std::tuple{-12.0, EiLayoutKind::Parallel},
                                           std::tuple{25.0, EiLayoutKind::Parallel},
                                           std::tuple{-25.0, EiLayoutKind::Parallel},
                                           std::tuple{16.0, EiLayoutKind::LensGrid},
                                           std::tuple{-16.0, EiLayoutKind::LensGrid}));

// Two objects at different depths: the front one (larger z, closer to the viewer) hides the
// back one in every pixel whose ray passes through both. One real, one virtual, with a
// placement (scale, translation) so the depth channel also checks the inverse transform.
TEST(Orthoscopic, FrontObjectOccludesBackObject) {
  Display disp = squareDisplay({.cols = 11, .rows = 9, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  Placement pl;
  pl.scale = Vec3d(2.0);
  pl.translateMm = {0.1, -0.2, 1.0};
  Transform T = pl.toDisplay();
  // Field frame: front sphere A (red), back sphere B (blue). Display: A at z = 1 + 2*2 = 5,
  // radius 1.2; B at z = 1 - 2*3 = -5, radius 3.
  MockSphere A{{0.0, 0.0, 2.0}, 0.6, Vec3(0.4f, 0.02f, 0.02f), 0.0, nullptr};
  MockSphere B{{0.0, 0.0, -3.0}, 1.5, Vec3(0.02f, 0.02f, 0.4f), 0.0, nullptr};
  MockField f({B, A}, FieldEncoding::RGB);  // order must not matter
  SynthesisSettings s = quietSettings(50.0);
  s.placement = pl;
  s.aovs = true;
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  const Vec3d cA = T.point(A.c), cB = T.point(B.c);
  const double rA = 2.0 * A.r, rB = 2.0 * B.r;
  int both = 0, bothOk = 0, onlyB = 0, onlyBOk = 0, depthOk = 0;
  for (int64_t i = 0; i < L.numRays(); ++i) {
    RayAddress a = rayAddress(L, i);
    RayD ray = pinholeRay(L, a);
    // The viewer's line of sight through this pixel, from the VCP into the scene.
    Vec3d o = ray.o + ray.d * (s.vcpMm / ray.d.z), dir = -ray.d;
    auto tA = sphereEntry(o, dir, cA, rA * 0.98), tB = sphereEntry(o, dir, cB, rB * 0.98);
    auto tAo = sphereEntry(o, dir, cA, rA * 1.02);
    PixelCoord px = eiaPixel(L, a);
    int x = L.panelCol0 + px.col, y = L.panelRow0 + px.row;
    float R = r.eia.at(x, y, 0), B_ = r.eia.at(x, y, 2);
    if (tA && tB) {
      ++both;
      if (R > 5.0f * B_) ++bothOk;
      auto tExact = sphereEntry(o, dir, cA, rA);
      double zA = tExact ? (o + *tExact * dir).z : 1e9;  // the front surface's display z
      if (std::abs(r.eia.at(x, y, 4) - zA) < 1e-3 && r.eia.at(x, y, 3) == 1.0f) ++depthOk;
    } else if (tB && !tAo) {
      ++onlyB;
      if (B_ > 5.0f * R) ++onlyBOk;
    }
  }
  EXPECT_GE(both, 100);
  EXPECT_EQ(bothOk, both) << "the back object showed through the front one";
  EXPECT_EQ(depthOk, both) << "depth channel is not the front surface's display z";
  EXPECT_GE(onlyB, 100);
  EXPECT_EQ(onlyBOk, onlyB);
  std::printf("  %d pixels see both (all show the front object), %d only the back one\n", both, onlyB);
}

// The VCP is the near plane: an object closer to the viewer than the VCP is not seen; moving
// the VCP beyond it brings it back.
TEST(Orthoscopic, VcpClipsWhatLiesInFrontOfIt) {
  Display disp = squareDisplay({.cols = 9, .rows = 7, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockSphere front{{0.0, 0.0, 14.0}, 1.5, Vec3(0.4f, 0.02f, 0.02f), 0.0, nullptr};
  MockSphere back{{0.0, 0.0, -20.0}, 12.0, Vec3(0.02f, 0.02f, 0.4f), 0.0, nullptr};
  MockField f({front, back}, FieldEncoding::RGB);
  auto redPixels = [&](double vcp, SynthesisStats* st) {
    SynthesisSettings s = quietSettings(50.0);
    s.vcpMm = vcp;
    SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
    *st = r.stats;
    int n = 0;
    for (int y = 0; y < r.eia.height; ++y)
      for (int x = 0; x < r.eia.width; ++x)
        if (r.eia.at(x, y, 0) > 5.0f * r.eia.at(x, y, 2)) ++n;
    return n;
  };
  SynthesisStats st;
  EXPECT_EQ(redPixels(10.0, &st), 0) << "an object in front of the VCP (z > D_VCP) appeared";
  EXPECT_FALSE(st.sceneBehindVcp);
  EXPECT_TRUE(st.sceneClipped);
  EXPECT_FALSE(st.notes.empty());
  EXPECT_TRUE(st.warnings.empty());
  EXPECT_GT(st.hitRays, 0u);
  EXPECT_GT(redPixels(30.0, &st), 50);
  EXPECT_FALSE(st.sceneClipped);
}

// The whole scene in front of the VCP: not an error, an empty EIA and a warning.
TEST(Orthoscopic, WholeSceneBehindVcpGivesEmptyEia) {
  Display disp = squareDisplay({.cols = 5, .rows = 5, .eiPx = 7});
  EiLayout L = computeLayout(disp);
  MockField f({{{0.0, 0.0, 0.0}, 2.0, Vec3(0.5f), 0.0, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s = quietSettings(50.0);
  s.vcpMm = 20.0;
  s.placement.translateMm = {0.0, 0.0, 40.0};
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  EXPECT_TRUE(r.stats.sceneBehindVcp);
  EXPECT_TRUE(r.stats.emptyEia);
  EXPECT_EQ(r.stats.hitRays, 0u);
  ASSERT_FALSE(r.stats.warnings.empty());
  EXPECT_NE(r.stats.warnings[0].find("empty"), std::string::npos);
  for (float v : r.eia.data) ASSERT_EQ(v, 0.0f);
}

// Toed-in: EI pitch P (1 + g/D), in the layout and in the synthesized EIA. An emitter at the
// viewpoint (0, 0, D) is seen by every EI through its lens centre at the EI centre, so the
// emitter's image steps by P (1 + g/D) from EI to EI.
TEST(Orthoscopic, ToedInEiPitch) {
  // Odd EI width, so the EI centre is a pixel centre and the emitter's image is not split.
  const double P = 1.1, g = 3.3, D = 60.0, p = 0.1;
  Display disp = squareDisplay({.cols = 9,
                                .rows = 5,
                                .eiPx = 11,
                                .pixelMm = p,
                                .gapMm = g,
                                .layout = EiLayoutKind::ToedIn,
                                .lensPitchMm = P,
                                .viewingDistanceMm = D});
  EiLayout L = computeLayout(disp);
  const double pitch = P * (1.0 + g / D);
  EXPECT_NEAR((L.eiCentreX(L.eiCols - 1) - L.eiCentreX(0)) / (L.eiCols - 1), pitch, p / (L.eiCols - 1));
  for (int k = 0; k < L.eiCols; ++k) EXPECT_NEAR(L.eiCentreX(k), L.lensX[size_t(k)] * (1.0 + g / D), 0.5 * p + 1e-9);

  const Point3d eye(0.0, 0.0, D);
  const double footprint = p * D / g;
  MockField f({{eye, 3.0 * footprint, Vec3(0.3f), footprint, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s = quietSettings(50.0);
  s.vcpMm = D + 20.0;
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  auto [seen, ok] = brightestMatchesPrediction(L, r.eia, eye);
  EXPECT_EQ(seen, L.eiCols * L.eiRows);
  EXPECT_GE(ok, int(std::ceil(0.95 * seen)));
  // Brightness-weighted centroid of the emitter's image in each EI of the middle row; a
  // least-squares line through them has slope P (1 + g/D) (not the parallel pitch n p = 1.0).
  const int l = L.eiRows / 2;
  double sk = 0, sx = 0, skk = 0, skx = 0;
  for (int k = 0; k < L.eiCols; ++k) {
    double wsum = 0, xsum = 0;
    for (int i = 0; i < L.eiW; ++i)
      for (int j = 0; j < L.eiH; ++j) {
        PixelCoord px = eiaPixel(L, {k, l, i, j});
        double w = brightness(r.eia, L.panelCol0 + px.col, L.panelRow0 + px.row);
        wsum += w;
        xsum += w * L.pixelCentreX(px.col);
      }
    ASSERT_GT(wsum, 0.0);
    double x = xsum / wsum;
    EXPECT_NEAR(x, L.eiCentreX(k), 0.5 * p + 0.02);
    sk += k, sx += x, skk += double(k) * k, skx += k * x;
  }
  const double n = L.eiCols;
  const double slope = (n * skx - sk * sx) / (n * skk - sk * sk);
  EXPECT_NEAR(slope, pitch, 0.01);
  EXPECT_GT(std::abs(slope - L.eiW * p), 0.05) << "indistinguishable from the parallel pitch";
  std::printf("  toed-in EI pitch from the synthesized EIA: %.4f mm (P (1 + g/D) = %.4f mm)\n", slope, pitch);
}
