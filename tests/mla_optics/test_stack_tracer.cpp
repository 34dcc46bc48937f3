// StackTracer (mla_optics/stack_tracer.h): real rays through optical stacks, against the exact
// cell-walking tracer of today's MLA, the first-order focal point of a compound stack, and the
// geometric limits of barrier walls and pinhole sheets; and StackMla, the view simulation's
// model of a stack display, against RealMla.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "core/rng.h"
#include "display/stack_first_order.h"
#include "mla_optics/stack_mla.h"
#include "mla_optics/stack_tracer.h"
#include "mla_test_util.h"

using namespace inim;
using namespace mla_test;

namespace {

Mla prototypeMla(Mla::Orientation o) {
  Mla m;
  m.pitchMm = 1.0;
  m.radiusMm = 1.62;
  m.substrateThicknessMm = 1.5;
  m.material = "PMMA";
  m.aperture = Mla::Aperture::Square;
  m.apertureMm = 1.0;
  m.orientation = o;
  return m;
}

StackLayer layer(StackLayer::Kind kind, double thickness) {
  StackLayer l;
  l.kind = kind;
  l.thicknessMm = thickness;
  l.pitchMm = 1.0;
  return l;
}

// Two PMMA plano-convex arrays 1.5 mm thick on 1 mm square cells, caps facing: the first's
// toward the viewer (R 1.62 mm), the second's toward the panel (R 2.4 mm).
std::pair<StackLayer, StackLayer> facingArrays() {
  StackLayer a = layer(StackLayer::Kind::LensArray, 1.5), b = a;
  a.material = b.material = "PMMA";
  a.aperture = b.aperture = Mla::Aperture::Square;
  a.apertureMm = b.apertureMm = 1.0;
  a.front.radiusMm = -1.62;
  b.back.radiusMm = 2.4;
  return {a, b};
}

}  // namespace

// Today's MLA as a stack: every ray from the panel (5,000 random rays up to 25 degrees, over
// several cells, crossing into neighbours, some reflected by TIR) leaves where and as the exact
// tracer says, to 1e-8 mm and 1e-9 in direction, with the same Fresnel weight.
TEST(StackTracer, AgreesWithTheExactTracerOfTodaysMla) {
  for (auto o : {kViewer, kPanel}) {
    Spec sp = spec(o);
    sp.gap = 3.3;
    const auto exact = makeMla(sp);
    const StackTracer stack(stackFromMla(prototypeMla(o), sp.gap), FresnelMode::Weighted);
    Rng rng(7, 1);
    int both = 0, agreeOnFate = 0;
    for (int i = 0; i < 5000; ++i) {
      const double x = -2.5 + 5.0 * rng.uniformDouble(), y = -2.5 + 5.0 * rng.uniformDouble();
      const Vec3d d = coneDirection(rng, 25.0);
      MlaExit ex;
      StackExit sx;
      const bool a = exact->traceToViewer({x, y, exact->panelZ()}, d, 550.0, nullptr, ex);
      const bool b = stack.trace({x, y, 0.0}, d, 550.0, nullptr, sx) && sx.towardViewer;
      agreeOnFate += a == b;
      if (!a || !b) continue;
      ++both;
      EXPECT_NEAR(sx.p.x, ex.p.x, 1e-8) << i;
      EXPECT_NEAR(sx.p.y, ex.p.y, 1e-8) << i;
      EXPECT_NEAR(sx.p.z, ex.p.z + sp.gap, 1e-8) << i;
      EXPECT_NEAR(glm::length(sx.d - ex.d), 0.0, 1e-9) << i;
      EXPECT_NEAR(sx.throughput, ex.throughput, 1e-9) << i;
    }
    EXPECT_EQ(agreeOnFate, 5000) << orientationName(o);
    EXPECT_GT(both, 4500) << orientationName(o);
  }
}

// A compound cell (two plano-convex arrays, caps facing): collimated rays from the viewer 5 um
// off a lenslet's axis cross it at the first-order front focal point F.
TEST(StackTracer, ACompoundCellFocusesAtItsFirstOrderFocalPoint) {
  OpticalStack s;
  auto [a, b] = facingArrays();
  b.back.conic = -0.3;
  s.layers = {layer(StackLayer::Kind::Gap, 3.0), a, layer(StackLayer::Kind::Gap, 1.0), b};
  const StackFirstOrder fo = stackFirstOrder(s, 550.0);
  const StackTracer tracer(s);
  StackExit ex;
  ASSERT_TRUE(tracer.trace({0.005, 0.0, tracer.frontZ() + 1.0}, {0.0, 0.0, -1.0}, 550.0, nullptr, ex));
  EXPECT_FALSE(ex.towardViewer);
  const double zAxis = ex.p.z - ex.p.x * ex.d.z / ex.d.x;
  EXPECT_NEAR(zAxis, fo.frontFocalZMm, 1e-4) << "first order F at z = " << fo.frontFocalZMm;
}

// The same pair of arrays in contact (no gap): the air lens their caps enclose between the
// touching vertices is traced as a region of its own, and a ray near the axis still crosses it
// at the first-order F (which treats the contact as two refractions with no air between); a
// ray through a cell's corner crosses the widest part of the air pocket and leaves.
TEST(StackTracer, LensArraysInContactEncloseAnAirLens) {
  OpticalStack s;
  auto [a, b] = facingArrays();
  s.layers = {layer(StackLayer::Kind::Gap, 3.0), a, b};
  const StackFirstOrder fo = stackFirstOrder(s, 550.0);
  ASSERT_FALSE(fo.afocal);
  const StackTracer tracer(s);
  StackExit ex;
  ASSERT_TRUE(tracer.trace({0.004, 0.0, tracer.frontZ() + 1.0}, {0.0, 0.0, -1.0}, 550.0, nullptr, ex));
  EXPECT_FALSE(ex.towardViewer);
  EXPECT_GE(ex.events, 4);  // into b, out of b into the air lens, into a, out of a
  const double zAxis = ex.p.z - ex.p.x * ex.d.z / ex.d.x;
  EXPECT_NEAR(zAxis, fo.frontFocalZMm, 1e-4) << "first order F at z = " << fo.frontFocalZMm;
  StackExit corner;
  ASSERT_TRUE(tracer.trace({0.0, 0.0, 0.0}, glm::normalize(Vec3d(0.49, 0.49, 3.0 + 1.5)), 550.0, nullptr, corner));
  EXPECT_TRUE(corner.towardViewer);
}

// Barrier walls h high: a ray from x0 inside a cell leaves iff it stays within the open part
// of its cell up to the walls' top, |x0 + h tan(theta)| < (P - w) / 2; nothing else is lost. As
// the walls grow (0.5 to 4 mm) they remove more of the rays that would cross into a neighbour
// cell, and at every height exactly those.
TEST(StackTracer, BarrierWallsRemoveExactlyTheRaysBeyondTheGeometricLimit) {
  for (double wall : {0.0, 0.1}) {
    int passedBelow = 1 << 30;
    for (double h : {0.5, 1.0, 2.0, 4.0}) {
      OpticalStack s;
      StackLayer barriers = layer(StackLayer::Kind::Barriers, h);
      barriers.wallMm = wall;
      s.layers = {barriers, layer(StackLayer::Kind::Gap, 1.0)};
      const StackTracer tracer(s);
      const double open = (1.0 - wall) / 2.0;
      int passed = 0, checked = 0;
      for (double x0 = -0.44; x0 <= 0.44; x0 += 0.0173)
        for (double deg = -30.0; deg <= 30.0; deg += 0.77) {
          const double reach = x0 + h * std::tan(deg * M_PI / 180.0);
          if (std::fabs(std::fabs(reach) - open) < 1e-6) continue;  // grazing a wall's top edge
          const Vec3d d(std::sin(deg * M_PI / 180.0), 0.0, std::cos(deg * M_PI / 180.0));
          StackExit ex;
          const bool out = tracer.trace({x0, 0.3, 0.0}, d, 550.0, nullptr, ex);
          EXPECT_EQ(out, std::fabs(reach) < open) << "x0 " << x0 << ", " << deg << " deg, wall " << wall << ", h " << h;
          passed += out;
          ++checked;
        }
      EXPECT_GT(passed, checked / 8) << h;
      EXPECT_LT(passed, checked) << h;
      EXPECT_LT(passed, passedBelow) << h;  // taller walls stop more
      passedBelow = passed;
    }
  }
}

// A pinhole sheet of no thickness 3 mm from the panel: a ray passes iff it crosses the sheet
// inside a hole, and leaves unbent.
TEST(StackTracer, APinholeSheetPassesOnlyRaysThroughItsHoles) {
  OpticalStack s;
  StackLayer sheet = layer(StackLayer::Kind::Apertures, 0.0);
  sheet.hole = Mla::Aperture::Circle;
  sheet.holeMm = 0.1;
  s.layers = {layer(StackLayer::Kind::Gap, 3.0), sheet, layer(StackLayer::Kind::Gap, 0.5)};
  const StackTracer tracer(s);
  Rng rng(3, 4);
  int passed = 0;
  for (int i = 0; i < 4000; ++i) {
    const Point3d o(-1.0 + 2.0 * rng.uniformDouble(), -1.0 + 2.0 * rng.uniformDouble(), 0.0);
    const Vec3d d = glm::normalize(Vec3d(0.3 * (rng.uniformDouble() - 0.5), 0.3 * (rng.uniformDouble() - 0.5), 1.0));
    const Point3d at = o + d * (3.0 / d.z);
    const double dx = at.x - std::round(at.x), dy = at.y - std::round(at.y), r = std::hypot(dx, dy);
    if (std::fabs(r - 0.05) < 1e-9) continue;
    StackExit ex;
    const bool out = tracer.trace(o, d, 550.0, nullptr, ex);
    EXPECT_EQ(out, r < 0.05) << i;
    if (out) {
      EXPECT_NEAR(glm::length(ex.d - d), 0.0, 1e-12);
    }
    passed += out;
  }
  EXPECT_GT(passed, 10);
}

// The view simulation's StackMla on today's MLA written as a stack: every camera ray reaches
// the panel where RealMla says (to float precision), through the same lenslet, with the same
// Fresnel weight (rays kept inside the array: the stack's lattice has no edge, the real sheet
// ends 4 lenslets beyond the EIs); and a gap other than the display's moves the panel with the
// first air gap.
TEST(StackMla, AgreesWithRealMlaOnTodaysMlaAsAStack) {
  Display d = smallDisplay(9, 7, 10, 0.1, 1.0, 3.3, 3.3);
  const EiLayout L = computeLayout(d);
  const auto real = RealMla::fromDisplay(d, L, d.reconstructionGapMm, RealMlaOptions{FresnelMode::Weighted});
  d.stack = stackFromMla(d.mla, d.reconstructionGapMm);
  d.stack->layers[1].material = d.mla.material.empty() ? "PMMA" : d.mla.material;
  d.stackTraced = true;
  const StackMla stack(d, L, d.reconstructionGapMm, FresnelMode::Weighted);
  EXPECT_NEAR(stack.frontZ(), real->frontZ(), 1e-5);
  Rng rng(11, 2);
  int reached = 0;
  for (int i = 0; i < 2000; ++i) {
    Ray ray;
    ray.o = Point3(float(-3.0 + 6.0 * rng.uniformDouble()), float(-2.5 + 5.0 * rng.uniformDouble()), 30.0f);
    ray.d = glm::normalize(Vec3(float(0.2 * (rng.uniformDouble() - 0.5)), float(0.2 * (rng.uniformDouble() - 0.5)), -1.0f));
    PanelArrival a, b;
    const bool ra = real->traceToPanel(ray, 550.0f, FresnelMode::Weighted, nullptr, a);
    const bool rb = stack.traceToPanel(ray, 550.0f, FresnelMode::Weighted, nullptr, b);
    ASSERT_EQ(ra, rb) << i;
    if (!ra) continue;
    ++reached;
    EXPECT_NEAR(b.p.x, a.p.x, 2e-5) << i;
    EXPECT_NEAR(b.p.y, a.p.y, 2e-5) << i;
    EXPECT_NEAR(b.p.z, a.p.z, 1e-5) << i;
    EXPECT_NEAR(glm::length(b.d - a.d), 0.0f, 1e-5f) << i;
    EXPECT_NEAR(b.throughput, a.throughput, 1e-6f) << i;
    EXPECT_EQ(b.lensletK, a.lensletK) << i;
    EXPECT_EQ(b.lensletL, a.lensletL) << i;
  }
  EXPECT_GT(reached, 1900);
  const StackMla farther(d, L, d.reconstructionGapMm + 0.5, FresnelMode::Weighted);
  Ray axial;
  axial.o = Point3(0.0f, 0.0f, 30.0f);
  axial.d = Vec3(0.0f, 0.0f, -1.0f);
  PanelArrival c;
  ASSERT_TRUE(farther.traceToPanel(axial, 550.0f, FresnelMode::Weighted, nullptr, c));
  EXPECT_FLOAT_EQ(c.p.z, float(-(d.reconstructionGapMm + 0.5)));
}

// A lossless stack (Fresnel off, no absorption, no sheets or walls): every ray from the panel
// leaves it, through the front or (after total internal reflection) back through the panel
// plane, or is still guided inside by TIR after the most events a trace allows, always with
// its full weight: the energy accounted for is the energy in, to 1e-6, for rays up to 60
// degrees over many cells of a compound stack with a plate; none is lost to the tracer.
TEST(StackTracer, ALosslessStackConservesEnergy) {
  OpticalStack s;
  StackLayer a = layer(StackLayer::Kind::LensArray, 1.5), b = a, plate = layer(StackLayer::Kind::Plate, 0.7);
  a.material = b.material = "PMMA";
  plate.material = "N-BK7";
  a.aperture = b.aperture = Mla::Aperture::Square;
  a.apertureMm = b.apertureMm = 1.0;
  a.front.radiusMm = -1.62;
  b.back.radiusMm = 2.4;
  s.layers = {layer(StackLayer::Kind::Gap, 3.0), a, layer(StackLayer::Kind::Gap, 1.0), b, plate};
  const StackTracer tracer(s);
  Rng rng(5, 9);
  double energyIn = 0.0, energyOut = 0.0;
  int back = 0, trapped = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3d d = coneDirection(rng, 60.0);
    StackExit ex;
    energyIn += 1.0;
    if (tracer.trace({-3.0 + 6.0 * rng.uniformDouble(), -3.0 + 6.0 * rng.uniformDouble(), 0.0}, d, 550.0, nullptr, ex))
      energyOut += ex.throughput;
    else if (ex.trapped)
      ++trapped, energyOut += ex.throughput;  // guided along the endless lattice by TIR: still inside
    back += !ex.towardViewer;
  }
  EXPECT_NEAR(energyOut / energyIn, 1.0, 1e-6);
  EXPECT_GT(back, 0);                 // some rays were turned back by total internal reflection
  EXPECT_LT(trapped, 20000 / 100);    // a few are guided (an endless lattice has no edge to leave by)
}

// A last surface concave toward the viewer rises above the stack's front plane at its cell
// borders: the tracer's front (where a view's rays enter) is its highest point, so rays from in
// front meet the whole face. Lossless, near normal incidence: every ray over the cell reaches
// the panel, and one crossing the face at a cell corner enters it above the front plane.
TEST(StackTracer, AConcaveFrontFaceAboveTheFrontPlaneIsMet) {
  OpticalStack s;
  StackLayer a = layer(StackLayer::Kind::LensArray, 0.5);
  a.material = "PMMA";
  a.apertureMm = 1.0;
  a.front.radiusMm = 4.0;  // concave toward the viewer
  s.layers = {layer(StackLayer::Kind::Gap, 2.0), a};
  const StackTracer tracer(s);
  const double rise = 4.0 - std::sqrt(16.0 - 0.5);  // the sag at a cell corner (r^2 = 0.5)
  EXPECT_NEAR(tracer.frontZ(), 2.5 + rise, 1e-6);
  int reached = 0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      StackExit ex;
      const Point3d o(-0.5 + i * 0.05, -0.5 + j * 0.05, tracer.frontZ() + 1e-6);  // just above, as a view starts
      if (tracer.trace(o, glm::normalize(Vec3d(0.01, 0.02, -1.0)), 550.0, nullptr, ex) && !ex.towardViewer) ++reached;
    }
  EXPECT_EQ(reached, 21 * 21);
  StackExit corner;
  ASSERT_TRUE(tracer.trace({0.5, 0.5, tracer.frontZ() + 1.0}, {0.0, 0.0, -1.0}, 550.0, nullptr, corner));
  EXPECT_FALSE(corner.towardViewer);
}

// Lenslets on 1 mm cells whose clear aperture is smaller than the cell (a 0.8 mm square on a square
// lattice, a 0.7 mm square on a hex one), flat or curved: caps inside, flat land at the caps'
// corner height outside, vertical walls between. A ray through the land at normal incidence
// passes straight, as through a plate (flat); rays hit the walls (the exits differ from the same array without walls);
// every path is reversible (traced back from where it left, a ray returns to its panel point, to
// 1e-7 mm; this needs rays that leave a cap to re-enter a neighbour that rises in their way); and
// with Fresnel off the energy is conserved.
static void expectWallsRefractAndConserveEnergy(Mla::Lattice lattice, Mla::Aperture shape, double aperture,
                                               const Point3d& landPoint, std::optional<StackCurvature> curvature = {}) {
  auto stack = [&](Mla::Aperture apertureShape, double size) {
    OpticalStack s;
    s.curvature = curvature;
    s.panelWidthMm = s.panelHeightMm = 10.0;
    StackLayer lens = layer(StackLayer::Kind::LensArray, 1.2);
    lens.material = "PMMA";
    lens.lattice = lattice;
    lens.aperture = apertureShape;
    lens.apertureMm = size;
    lens.front.radiusMm = -1.0;
    s.layers = {layer(StackLayer::Kind::Gap, 2.0), lens};
    return s;
  };
  const StackTracer walled(stack(shape, aperture)),
      open(stack(lattice == Mla::Lattice::Hex ? Mla::Aperture::Hex : Mla::Aperture::Square, 1.0));
  StackExit land;
  ASSERT_TRUE(walled.trace(landPoint, {0.0, 0.0, 1.0}, 550.0, nullptr, land));
  EXPECT_TRUE(land.towardViewer);
  if (!curvature) EXPECT_NEAR(glm::length(land.d - Vec3d(0.0, 0.0, 1.0)), 0.0, 1e-12);  // curved: a bent plate
  // Whether the ray that left at `a` returns, traced back from just in front, to (o, -d).
  auto retraces = [](const StackTracer& t, const StackExit& a, const Point3d& o, const Vec3d& d) {
    StackExit back;
    const Point3d start = a.p + a.d * (std::max(0.0, (t.frontZ() - a.p.z) / a.d.z) + 1e-6);
    if (!t.trace(start, -a.d, 550.0, nullptr, back) || back.towardViewer) return false;
    const Point3d at = back.p + back.d * (-back.p.z / back.d.z);  // on the panel plane
    return std::hypot(at.x - o.x, at.y - o.y) < 1e-7 && glm::length(back.d + d) < 1e-7;
  };
  Rng rng(3, 4);
  int differ = 0, left[2] = {0, 0}, reversed[2] = {0, 0};
  double energyOut = 0.0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const Vec3d d = coneDirection(rng, 50.0);
    const Point3d o(-1.0 + 2.0 * rng.uniformDouble(), -1.0 + 2.0 * rng.uniformDouble(), 0.0);
    StackExit a, b;
    const bool ra = walled.trace(o, d, 550.0, nullptr, a), rb = open.trace(o, d, 550.0, nullptr, b);
    if (ra || a.trapped) energyOut += a.throughput;
    if (ra != rb || (ra && glm::length(a.d - b.d) > 1e-6)) ++differ;
    if (ra && a.towardViewer) ++left[0], reversed[0] += retraces(walled, a, o, d);
    if (rb && b.towardViewer) ++left[1], reversed[1] += retraces(open, b, o, d);
  }
  EXPECT_GT(differ, n / 50);  // the walls and the land change what the caps did
  for (int k : {0, 1}) {
    EXPECT_GT(left[k], n / 2);
    EXPECT_GE(reversed[k], left[k] - left[k] / 100) << k;  // all but long TIR-guided paths (20+ events)
  }
  EXPECT_NEAR(energyOut / n, 1.0, 1e-6);
}

TEST(StackTracer, WallsBetweenCapsRefractAndConserveEnergy) {
  expectWallsRefractAndConserveEnergy(Mla::Lattice::Square, Mla::Aperture::Square, 0.8, {0.45, 0.45, 0.0});
}

// A square aperture on a hex lattice (its cells' flats 1 mm apart, vertical): the land between
// the square and the hexagon at (0.45, 0); a hex aperture (0.8 mm across its vertical flats) on a
// square lattice, whose edges are found by stepping along the ray: the land at (0.45, 0.45).
TEST(StackTracer, AnApertureOfAnotherShapeThanItsCellHasWallsToo) {
  expectWallsRefractAndConserveEnergy(Mla::Lattice::Hex, Mla::Aperture::Square, 0.7, {0.45, 0.0, 0.0});
  expectWallsRefractAndConserveEnergy(Mla::Lattice::Square, Mla::Aperture::Hex, 0.8, {0.45, 0.45, 0.0});
}

// Curved arrays (a sphere of 60 mm, centre behind; a cylinder of 80 mm, centre in front): square
// apertures' walls stand on planes through the centre of curvature, hex apertures' are stepped
// to, and the same holds.
TEST(StackTracer, WallsBetweenTheCapsOfACurvedArray) {
  expectWallsRefractAndConserveEnergy(Mla::Lattice::Square, Mla::Aperture::Square, 0.8, {0.45, 0.45, 0.0},
                                      StackCurvature{StackCurvature::Shape::Sphere, -60.0});
  expectWallsRefractAndConserveEnergy(Mla::Lattice::Hex, Mla::Aperture::Square, 0.7, {0.45, 0.0, 0.0},
                                      StackCurvature{StackCurvature::Shape::Cylinder, 80.0});
  expectWallsRefractAndConserveEnergy(Mla::Lattice::Hex, Mla::Aperture::Hex, 0.8, {0.45, 0.0, 0.0},
                                      StackCurvature{StackCurvature::Shape::Sphere, 90.0});
}
