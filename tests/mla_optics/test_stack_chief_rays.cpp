// Chief rays traced through an optical stack (mla_optics/stack_chief_rays.h): the aperture stop
// found to first order, the traced chief rays against the exact real-lens chief rays of today's
// MLA, the pinhole model (a pinhole sheet), the first-order chief ray near the axis of a
// compound cell, and the offset table against solving every pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "core/parallel.h"
#include "display/stack_first_order.h"
#include "mla_optics/real_lens_rays.h"
#include "mla_optics/stack_chief_rays.h"
#include "mla_optics/stack_tracer.h"
#include "mla_test_util.h"
#include "rays/pinhole_rays.h"

using namespace inim;
using namespace mla_test;

namespace {

StackLayer layer(StackLayer::Kind kind, double thickness, double pitch = 1.0) {
  StackLayer l;
  l.kind = kind;
  l.thicknessMm = thickness;
  l.pitchMm = pitch;
  l.keyPath = "stack.layers[?]";
  return l;
}

// A compound cell: two PMMA plano-convex arrays, caps facing, an aperture sheet between them.
OpticalStack compoundCell(double holeMm) {
  OpticalStack s;
  StackLayer a = layer(StackLayer::Kind::LensArray, 1.0), b = a;
  a.material = b.material = "PMMA";
  a.apertureMm = b.apertureMm = 1.0;
  a.front.radiusMm = -2.0;
  b.back.radiusMm = 2.0;
  StackLayer sheet = layer(StackLayer::Kind::Apertures, 0.0);
  sheet.holeMm = holeMm;
  s.layers = {layer(StackLayer::Kind::Gap, 2.5), a, layer(StackLayer::Kind::Gap, 0.4), sheet,
              layer(StackLayer::Kind::Gap, 0.4), b};
  for (size_t i = 0; i < s.layers.size(); ++i) s.layers[i].keyPath = "stack.layers[" + std::to_string(i) + "]";
  return s;
}

double rayAngle(const RaySet& a, const RaySet& b, size_t i) {
  return angle(unit(Vec3d(a.ray(i).d)), unit(Vec3d(b.ray(i).d)));
}

}  // namespace

// The stop of each kind of stack: the cap of a plano-convex lenslet facing the viewer (the
// diverging axial bundle is widest there), the sheet of a compound cell when its hole is smaller
// than the lenses, the second lens when the sheet's hole is wider than the cone the lenses pass.
TEST(StackChiefRays, TheApertureStopIsTheNarrowestOpeningAtFirstOrder) {
  Mla m;
  m.pitchMm = 1.0, m.radiusMm = 1.62, m.substrateThicknessMm = 1.5, m.material = "PMMA";
  m.aperture = Mla::Aperture::Square, m.apertureMm = 1.0, m.orientation = Mla::Orientation::CurvedTowardViewer;
  const auto plano = findApertureStop(stackFromMla(m, 3.3), kLambdaDNm);
  ASSERT_TRUE(plano);
  EXPECT_EQ(plano->layer, 1u);
  EXPECT_TRUE(plano->front);

  const auto narrow = findApertureStop(compoundCell(0.3), kLambdaDNm);
  ASSERT_TRUE(narrow);
  EXPECT_EQ(narrow->layer, 3u);
  EXPECT_NEAR(narrow->radiusMm, 0.15, 1e-15);
  const auto wide = findApertureStop(compoundCell(5.0), kLambdaDNm);
  ASSERT_TRUE(wide);
  EXPECT_EQ(wide->layer, 5u);
  // The stop's first-order height of the axial marginal ray is the system matrix's B there.
  const std::vector<ParaxialPlane> planes = stackParaxialPlanes(compoundCell(0.3), kLambdaDNm);
  EXPECT_DOUBLE_EQ(narrow->b, planes[6].b);
  EXPECT_DOUBLE_EQ(planes[1].b, 2.5);  // the first gap: air, B = thickness
}

// Today's MLA (cap toward the viewer) as a one-layer stack: every pixel's traced chief ray is
// the exact real-lens chief ray through the cap vertex (real_lens_rays.h, solved directly) to
// 1e-9 rad, and its origin on z = 0 to 1e-8 mm; the offset table is within 2e-6 rad of it.
TEST(StackChiefRays, OnTodaysMlaTheyAreTheRealLensChiefRays) {
  Display d = smallDisplay(7, 5, 10, 0.1, 1.0, 3.3, 3.3);
  d.mla.orientation = Mla::Orientation::CurvedTowardViewer;
  d.mla.material = "PMMA";
  const EiLayout L = computeLayout(d);
  const auto real = RealMla::fromDisplay(d, L, L.gapMm);
  RealLensRayOptions ro;
  ro.model = RealLensRayModel::Chief;
  ro.tableStepMm = 0.0;
  const RaySet exact = generateRealLensRays(L, *real, ro);
  TracedChiefRayOptions direct;
  direct.tableStepMm = 0.0;
  TracedChiefRayStats st;
  const RaySet traced = generateTracedChiefRays(L, stackFromMla(d.mla, L.gapMm), L.gapMm, direct, &st);
  const RaySet tabled = generateTracedChiefRays(L, stackFromMla(d.mla, L.gapMm), L.gapMm, TracedChiefRayOptions{});
  ASSERT_EQ(traced.size(), exact.size());
  EXPECT_EQ(st.fallback, 0u);
  EXPECT_GT(st.maxDeviationDeg, 0.02);  // refraction bends them away from the pinhole rays
  double worst = 0.0, worstTable = 0.0, worstOrigin = 0.0;
  for (size_t i = 0; i < exact.size(); ++i) {
    worst = std::max(worst, rayAngle(traced, exact, i));
    worstTable = std::max(worstTable, rayAngle(tabled, traced, i));
    worstOrigin = std::max(worstOrigin, double(glm::length(traced.ray(i).o - exact.ray(i).o)));
  }
  EXPECT_LT(worst, 1e-6);   // float storage: 6e-8 rad per component at most
  EXPECT_LT(worstOrigin, 1e-5);
  EXPECT_LT(worstTable, 2e-6);
}

// A pinhole sheet (no thickness, no lens) at the gap: each pixel's chief ray runs straight
// through its hole's centre, which is the pinhole model's ray through the lens centre when the
// EI pitch is the lens pitch.
TEST(StackChiefRays, APinholeSheetGivesThePinholeModelsRays) {
  const Display d = smallDisplay(7, 5, 10, 0.1, 1.0, 3.3, 3.3);  // EIs of 10 x 0.1 mm on a 1 mm pitch
  const EiLayout L = computeLayout(d);
  OpticalStack s;
  StackLayer sheet = layer(StackLayer::Kind::Apertures, 0.0);
  sheet.holeMm = 0.1;
  s.layers = {layer(StackLayer::Kind::Gap, L.gapMm), sheet};
  TracedChiefRayStats st;
  const RaySet traced = generateTracedChiefRays(L, s, L.gapMm, TracedChiefRayOptions{}, &st);
  const RaySet pinhole = generatePinholeRays(L);
  ASSERT_EQ(traced.size(), pinhole.size());
  EXPECT_EQ(st.fallback, 0u);
  for (size_t i = 0; i < traced.size(); ++i) {
    ASSERT_LT(rayAngle(traced, pinhole, i), 1e-6) << i;
    ASSERT_LT(glm::length(traced.ray(i).o - pinhole.ray(i).o), 1e-6f) << i;
  }
}

// Near the axis a compound cell's traced chief ray is the first-order chief ray: the launch
// slope that puts the stop crossing on the axis (u0 = -A y0 / (B n0)) leaves the stack with slope
// C y0 + D u0 (the system matrix), to 1e-4 relative for a pixel 1 um off the axis; farther out it
// departs from it as the cube of the height (third-order distortion).
TEST(StackChiefRays, NearTheAxisTheyAreTheFirstOrderChiefRay) {
  const OpticalStack s = compoundCell(0.3);
  const StackFirstOrder fo = stackFirstOrder(s);
  const std::optional<ApertureStop> stop = findApertureStop(s, kLambdaDNm);
  ASSERT_TRUE(stop);
  const StackChiefRaySolver solver(s, 0.0, 0.0, kLambdaDNm);
  const double y0 = 1e-3;
  Point3d p;
  Vec3d d;
  ASSERT_TRUE(solver.solve(y0, 0.0, 0.0, 0.0, p, d));
  const double u0 = -stop->a * y0 / stop->b, expected = fo.c * y0 + fo.d * u0;
  EXPECT_NEAR(d.x / d.z, expected, 1e-4 * std::fabs(expected));
  EXPECT_NEAR(d.y, 0.0, 1e-15);

  // Farther out it departs from first order as the cube of the height (distortion, a
  // third-order aberration): twice the height, eight times the departure.
  auto departure = [&](double y) {
    EXPECT_TRUE(solver.solve(y, 0.0, 0.0, 0.0, p, d));
    return d.x / d.z - (fo.c * y - fo.d * stop->a * y / stop->b);
  };
  const double ratio = departure(0.2) / departure(0.1);
  EXPECT_NEAR(ratio, 8.0, 0.4);
  EXPECT_GT(std::fabs(departure(0.4)), 1e-6);
}

// A stack without an aperture (only gaps and a plate) has no chief rays: InputError naming the
// stack.
TEST(StackChiefRays, AStackWithoutAStopIsRefused) {
  OpticalStack s;
  s.file = "plates.json";
  StackLayer plate = layer(StackLayer::Kind::Plate, 1.0, 0.0);
  plate.material = "N-BK7";
  s.layers = {layer(StackLayer::Kind::Gap, 2.0, 0.0), plate};
  EXPECT_FALSE(findApertureStop(s, kLambdaDNm));
  try {
    StackChiefRaySolver solver(s, 0.0, 0.0, kLambdaDNm);
    FAIL() << "accepted a stack without a stop";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("plates.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stack"), std::string::npos) << e.what();
  }
}

// Hard case: EIs (1 mm) wider than the lenslets' cells (0.9 mm) behind barrier walls, so the
// outer EIs' outer pixels lie under a neighbour's cell and their chief ray toward their own
// lenslet runs into a wall. Those pixels fall back to the pinhole ray through their lens centre
// (counted), every ray is finite and unit, and the rays are the same bytes on 1 and 2 threads.
TEST(StackChiefRays, PixelsWhoseChiefRayAWallStopsFallBackToThePinholeRay) {
  const Display d = smallDisplay(9, 7, 10, 0.1, 0.9, 3.0, 3.3);
  const EiLayout L = computeLayout(d);
  OpticalStack s;
  StackLayer walls = layer(StackLayer::Kind::Barriers, 1.5, 0.9);
  walls.wallMm = 0.05;
  StackLayer lens = layer(StackLayer::Kind::LensArray, 1.0, 0.9);
  lens.material = "PMMA";
  lens.apertureMm = 0.9;
  lens.front.radiusMm = -1.5;
  s.layers = {layer(StackLayer::Kind::Gap, 0.3, 0.0), walls, layer(StackLayer::Kind::Gap, 1.0, 0.0), lens};
  TracedChiefRayStats st;
  RaySet one, two;
  {
    ThreadLimit t(1);
    one = generateTracedChiefRays(L, s, 3.3, TracedChiefRayOptions{}, &st);
  }
  {
    ThreadLimit t(2);
    two = generateTracedChiefRays(L, s, 3.3, TracedChiefRayOptions{});
  }
  EXPECT_GT(st.fallback, 0u);
  EXPECT_LT(st.fallback, st.rays / 2);
  EXPECT_EQ(one.ox, two.ox);
  EXPECT_EQ(one.dx, two.dx);
  EXPECT_EQ(one.dz, two.dz);
  size_t pinholeLike = 0;
  for (size_t i = 0; i < one.size(); ++i) {
    const Ray r = one.ray(i);
    ASSERT_TRUE(std::isfinite(r.o.x) && std::isfinite(r.d.x) && std::isfinite(r.d.z)) << i;
    ASSERT_NEAR(glm::length(r.d), 1.0f, 1e-6f) << i;
    ASSERT_GT(r.d.z, 0.0f) << i;
    pinholeLike += r.o.z == 0.0f && std::fabs(std::fmod(std::fabs(r.o.x) + 1e-6, 0.9)) < 1e-5;
  }
  EXPECT_GE(pinholeLike, st.fallback);  // the fallbacks start on a lens centre
}
