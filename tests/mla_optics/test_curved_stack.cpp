// Curved optical stacks through the tracer, the chief-ray solver and the view simulation's
// models (mla_optics/stack_tracer.h, stack_chief_rays.h, stack_mla.h): a concentric array whose
// EI-centre chief rays all pass through the centre of curvature, a cylinder's lenslets as exact
// rotations of one another, energy and reversibility through a lossless curved stack, the flat
// limit of a huge radius, a bent plate's first-order power (the thick meniscus), and a camera
// ray along a lenslet's axis reaching the panel where the layout centres its EI.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "display/ei_layout.h"
#include "display/stack_first_order.h"
#include "mla_optics/stack_chief_rays.h"
#include "mla_optics/stack_mla.h"
#include "mla_optics/stack_tracer.h"
#include "mla_test_util.h"

using namespace inim;
using namespace mla_test;

namespace {

StackLayer layer(StackLayer::Kind kind, double thickness) {
  StackLayer l;
  l.kind = kind;
  l.thicknessMm = thickness;
  l.pitchMm = 1.0;
  l.keyPath = "stack.layers[?]";
  return l;
}

// A gap of 3 mm and today's plano-convex PMMA lenslets (R 1.62 mm toward the viewer, 1.5 mm
// thick, 1 mm square cells), bent as asked, over a 40 x 30 mm panel.
OpticalStack curvedArray(StackCurvature::Shape shape, double radius, std::optional<double> panelRadius = {}) {
  OpticalStack s;
  StackLayer lens = layer(StackLayer::Kind::LensArray, 1.5);
  lens.material = "PMMA";
  lens.aperture = Mla::Aperture::Square;
  lens.apertureMm = 1.0;
  lens.front.radiusMm = -1.62;
  s.layers = {layer(StackLayer::Kind::Gap, 3.0), lens};
  s.curvature = StackCurvature{shape, radius};
  s.panelRadiusMm = panelRadius;
  s.panelWidthMm = 40.0, s.panelHeightMm = 30.0;
  return s;
}

// Distance from point c to the line through p along unit d.
double lineDistance(const Point3d& p, const Vec3d& d, const Point3d& c) { return glm::length(glm::cross(c - p, d)); }

}  // namespace

// A concentric array (panel and lenslets on shells about one centre): the chief ray of every
// EI's centre pixel (where its lenslet's axis meets the panel) leaves along that axis, so all of
// them, traced for real through each lenslet, pass through the centre of curvature (a cylinder's
// axis; 1e-6 mm at up to 83 mm: 1.2e-8 rad),
// for cylinders and spheres, centre in front or behind; and a flat panel changes nothing for
// those pixels, which lie on the axes too.
TEST(CurvedStack, ConcentricChiefRaysAllPassThroughTheCentreOfCurvature) {
  for (auto shape : {StackCurvature::Shape::Cylinder, StackCurvature::Shape::Sphere})
    for (double R : {-60.0, 80.0})
      for (bool concentric : {true, false}) {
        const OpticalStack s = curvedArray(shape, R, concentric ? std::optional<double>(3.0 + R) : std::nullopt);
        const StackChiefRaySolver solver(s, 0.0, 0.0, kLambdaDNm);
        const Point3d c = s.arrayFrame().centre();
        int solved = 0;
        for (double X = -15.0; X <= 15.0; X += 5.0)
          for (double Y = -10.0; Y <= 10.0; Y += 5.0) {
            double px, py;
            axisFootOnPanel(s, X, Y, px, py);
            Point3d p;
            Vec3d d;
            ASSERT_TRUE(solver.solve(px, py, X, Y, p, d)) << X << ", " << Y;
            // A cylinder's centre of curvature for this lenslet: its axis's point level with it.
            const Point3d cl = c + Vec3d(0.0, shape == StackCurvature::Shape::Cylinder ? Y : 0.0, 0.0);
            EXPECT_LT(lineDistance(p, d, cl), 1e-6) << R << " " << X << ", " << Y;
            ++solved;
          }
        EXPECT_EQ(solved, 35);
      }
}

// A concentric cylinder's lenslets are rotations of one another about its axis: a pixel 0.3 mm
// (of panel arc) off lenslet k's EI centre has the chief ray of the same pixel under lenslet 0,
// rotated by lenslet k's angle, to 1e-9 rad.
TEST(CurvedStack, ACylindersLensletsAreRotationsOfOneAnother) {
  const double R = -60.0;
  const OpticalStack s = curvedArray(StackCurvature::Shape::Cylinder, R, 3.0 + R);
  const StackChiefRaySolver solver(s, 0.0, 0.0, kLambdaDNm);
  auto rayOf = [&](double X) {
    double px, py;
    axisFootOnPanel(s, X, 0.0, px, py);
    Point3d p;
    Vec3d d;
    EXPECT_TRUE(solver.solve(px + 0.3, py + 0.2, X, 0.0, p, d));
    return d;
  };
  const Vec3d d0 = rayOf(0.0);
  EXPECT_GT(angle(d0, {0.0, 0.0, 1.0}), 0.01);  // a ray well off the axis
  for (double X : {-12.0, 7.0, 15.0}) {
    const double a = X / std::fabs(R);  // the lenslet's angle about the cylinder's axis (y)
    const Vec3d d = rayOf(X);
    const Vec3d back(d.x * std::cos(a) - d.z * std::sin(a), d.y, d.x * std::sin(a) + d.z * std::cos(a));
    EXPECT_LT(angle(back, d0), 1e-9) << X;
  }
}

// Lossless (Fresnel off, nothing absorbs): every ray from a flat panel under a spherical compound
// stack with a bent plate leaves it (in front, back through the panel, or around the array's
// edge after TIR has guided it there) or is still guided inside, with its full weight (energy
// to 1e-6); and the paths are reversible: traced back from where it left in front, a ray returns
// to its panel point, to 1e-6 mm for 99 % of them (the rest: long TIR paths that graze a cap,
// where 1e-12 grows to 1e-5 mm over dozens of bounces).
TEST(CurvedStack, ALosslessCurvedStackConservesEnergyAndIsReversible) {
  // Centre behind (the array's edges dip toward the flat panel: 2.1 mm at 25 mm off the axis) and
  // in front.
  for (double R : {-150.0, 90.0}) {
    OpticalStack s = curvedArray(StackCurvature::Shape::Sphere, R);
    StackLayer second = layer(StackLayer::Kind::LensArray, 1.5), plate = layer(StackLayer::Kind::Plate, 0.7);
    second.material = "PMMA", second.aperture = Mla::Aperture::Square, second.apertureMm = 1.0;
    second.back.radiusMm = 2.4;
    plate.material = "N-BK7";
    s.layers.push_back(layer(StackLayer::Kind::Gap, 1.0));
    s.layers.push_back(second);
    s.layers.push_back(plate);
    const StackTracer tracer(s);
    Rng rng(5, 3);
    double in = 0.0, out = 0.0;
    int reversed = 0, exact = 0, front = 0, edge = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3d d = coneDirection(rng, 50.0);
      const Point3d o(-10.0 + 20.0 * rng.uniformDouble(), -8.0 + 16.0 * rng.uniformDouble(), 0.0);
      StackExit ex;
      in += 1.0;
      const bool left = tracer.trace(o, d, 550.0, nullptr, ex);
      if (left || ex.trapped) out += ex.throughput;
      edge += ex.aroundEdge;
      if (!left || !ex.towardViewer) continue;
      ++front;
      StackExit back;
      const Point3d start = ex.p + 50.0 * ex.d;  // in front of the stack (not around its far edge)
      if (start.z <= tracer.frontZ() || !tracer.trace(start, -ex.d, 550.0, nullptr, back) || back.towardViewer) continue;
      ++reversed;
      exact += glm::length(back.p - o) < 1e-6;
    }
    EXPECT_NEAR(out / in, 1.0, 1e-6) << R;
    EXPECT_GT(front, 2000) << R;
    EXPECT_LT(edge, 4000 / 10) << R;             // guided by TIR to the array's edge, 22 mm out
    EXPECT_GT(reversed, front * 95 / 100) << R;  // the rest meet the stack again on the way back in
    EXPECT_GT(exact, reversed * 99 / 100) << R << ": " << exact << " of " << reversed << ", " << edge << " around the edge";
  }
}

// Barrier walls in a curved stack stand on the cells' borders (square cells: planes through the
// centre of curvature; hex cells: their hexagons in the arc coordinates): absorbing, they stop
// exactly the rays whose straight path through the wall layer ends in another cell than it began
// (judged by the frame's arc coordinates), and pass the rest unchanged; mirrors (reflectance 1),
// they lose nothing (energy to 1e-6).
TEST(CurvedStack, BarrierWallsStandOnTheCellBordersThroughTheCentre) {
  auto cellOf = [](bool hex, const Vec3d& q) {  // the nearest lattice point (pitch 1, origin 0)
    if (!hex) return std::make_pair(double(std::lround(q.x)), double(std::lround(q.y)));
    const double rowH = std::sqrt(3.0) / 2.0;
    std::pair<double, double> best{0.0, 0.0};
    double bestD = 1e300;
    for (double l = std::floor(q.y / rowH); l <= std::floor(q.y / rowH) + 1.0; l += 1.0) {
      const double shift = std::fmod(std::fabs(l), 2.0) == 1.0 ? 0.5 : 0.0, x = shift + std::round(q.x - shift);
      const double d2 = (x - q.x) * (x - q.x) + (l * rowH - q.y) * (l * rowH - q.y);
      if (d2 < bestD) bestD = d2, best = {x, l};
    }
    return best;
  };
  for (auto lattice : {Mla::Lattice::Square, Mla::Lattice::Hex})
    for (auto shape : {StackCurvature::Shape::Cylinder, StackCurvature::Shape::Sphere})
      for (double R : {-150.0, 120.0}) {  // behind: the array dips 0.55 mm at the corners
        OpticalStack s = curvedArray(shape, R);
        StackLayer walls = layer(StackLayer::Kind::Barriers, 2.5);
        walls.lattice = lattice;
        s.layers = {layer(StackLayer::Kind::Gap, 1.0), walls};
        const CurvedFrame frame = s.arrayFrame();
        const StackTracer absorbing(s);
        s.layers[1].reflectance = 1.0;
        const StackTracer mirrors(s);
        Rng rng(4, 7);
        int passed = 0, stopped = 0;
        double energy = 0.0;
        for (int i = 0; i < 3000; ++i) {
          const Vec3d d = coneDirection(rng, 40.0);
          const Point3d o(-10.0 + 20.0 * rng.uniformDouble(), -8.0 + 16.0 * rng.uniformDouble(), 0.0);
          double t0, t1;
          ASSERT_TRUE(frame.hitShell(o, d, 1.0, 0.0, 1e9, t0) && frame.hitShell(o, d, 3.5, 0.0, 1e9, t1));
          const bool hex = lattice == Mla::Lattice::Hex;
          const bool sameCell = cellOf(hex, frame.toFrame(o + t0 * d)) == cellOf(hex, frame.toFrame(o + t1 * d));
          StackExit ex;
          const bool left = absorbing.trace(o, d, 550.0, nullptr, ex) && ex.towardViewer;
          EXPECT_EQ(left, sameCell) << int(lattice) << " " << R << " " << i;
          if (left) EXPECT_LT(angle(ex.d, d), 1e-12) << i;
          passed += left, stopped += !left;
          StackExit m;
          if (mirrors.trace(o, d, 550.0, nullptr, m) || m.trapped) energy += m.throughput;
        }
        EXPECT_GT(passed, 200);
        EXPECT_GT(stopped, 300);
        EXPECT_NEAR(energy / 3000.0, 1.0, 1e-6);
      }
}

// A radius of 1e7 mm is flat to 1e-6 mm over the few cells the rays cross: the curved tracer
// (shells, the march in the bent frame, gradient normals) gives the flat tracer's exits, to
// 1e-5 mm and 5e-6 rad.
TEST(CurvedStack, AHugeRadiusIsTheFlatStack) {
  const OpticalStack curved = curvedArray(StackCurvature::Shape::Sphere, 1e7);
  OpticalStack flat = curved;
  flat.curvature.reset();
  const StackTracer a(curved), b(flat);
  Rng rng(8, 2);
  int both = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3d d = coneDirection(rng, 30.0);
    const Point3d o(-3.0 + 6.0 * rng.uniformDouble(), -3.0 + 6.0 * rng.uniformDouble(), 0.0);
    StackExit x, y;
    const bool ra = a.trace(o, d, 550.0, nullptr, x), rb = b.trace(o, d, 550.0, nullptr, y);
    ASSERT_EQ(ra, rb) << i;
    if (!ra) continue;
    ++both;
    EXPECT_LT(glm::length(x.p - y.p), 1e-5) << i;
    EXPECT_LT(angle(x.d, y.d), 5e-6) << i;  // the shells' own tilt, x / R: 3e-7 rad, twice refracted
    EXPECT_EQ(x.towardViewer, y.towardViewer) << i;
  }
  EXPECT_GT(both, 900);
}

// A flat-faced layer bent onto two concentric shells is a meniscus: its first-order focal length
// is the thick lens's, 1/f = (n - 1) (1/R1 - 1/R2 + (n - 1) t / (n R1 R2)), R1 and R2 the shells'
// radii (signed as the lens convention signs them), to 1e-12 relative.
TEST(CurvedStack, ABentPlateHasTheThickMeniscusPower) {
  for (double R : {50.0, -40.0}) {
    OpticalStack s = curvedArray(StackCurvature::Shape::Sphere, R);
    s.layers[1].front = StackSurface{};
    s.layers[1].thicknessMm = 2.0;
    const double n = MaterialCatalog::standard().dielectric("PMMA")->n(float(kLambdaDNm));
    const double r1 = R, r2 = R - 2.0;  // the front shell's signed radius, 2 mm on
    const double power = (n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * 2.0 / (n * r1 * r2));
    EXPECT_NEAR(stackFirstOrder(s).focalLengthMm * power, 1.0, 1e-12) << R;
  }
}

// The view simulation on a curved display (a 9 x 7 EI display on the test panel, square and hex
// lattices, a concentric spherical panel and a flat one): a camera ray along lenslet (k, l)'s
// axis enters its vertex square on and reaches the panel where that axis meets it, where the
// layout centres EI (k, l) (to half a pixel; a hex EI's centre exactly), through lenslet (k, l);
// the ideal model sends it to the same point.
TEST(CurvedStack, ARayAlongALensletsAxisReachesItsEiCentre) {
  for (auto lattice : {Mla::Lattice::Square, Mla::Lattice::Hex})
    for (bool concentric : {true, false}) {
      Display d = smallDisplay(9, 7, 9, 0.1, 1.0, 3.3, 4.0, 6);  // 0.9 mm EIs: the axes converge on the panel
      OpticalStack s = curvedArray(StackCurvature::Shape::Sphere, -40.0, concentric ? std::optional<double>(-37.0) : std::nullopt);
      s.layers[1].lattice = lattice;
      if (lattice == Mla::Lattice::Hex) s.layers[1].aperture = Mla::Aperture::Hex;
      s.panelWidthMm = d.panel.widthPx * d.panel.pixelPitchMm, s.panelHeightMm = d.panel.heightPx * d.panel.pixelPitchMm;
      d.stack = s;
      const StackAsMla eq = equivalentMla(s);
      d.mla = eq.mla, d.reconstructionGapMm = eq.gapMm, d.stackTraced = true;
      const EiLayout L = computeLayout(d);
      const StackMla real(d, L, d.reconstructionGapMm, FresnelMode::Off);
      const CurvedIdealMla ideal(d, L, *d.mla.focalLengthMm, d.reconstructionGapMm);
      const CurvedFrame frame = s.arrayFrame();
      const double tolerance = lattice == Mla::Lattice::Hex ? 1e-12 : 0.5 * L.pixelMm + 1e-12;
      for (int k : {0, 3, 8})
        for (int l : {0, 3, 4, 6}) {
          const double X = L.lensXAt(k, l), Y = L.lensYAt(k, l);
          double fx, fy;
          axisFootOnPanel(s, X, Y, fx, fy);
          EXPECT_NEAR(L.eiCentreXAt(k, l), fx, tolerance) << k << ", " << l;
          EXPECT_NEAR(L.eiCentreYAt(k, l), fy, tolerance) << k << ", " << l;
          const Point3d top = frame.toWorld(X, Y, 30.0);  // on the axis, in front
          Ray ray;
          ray.o = Point3(Vec3d(top) - Vec3d(0.0, 0.0, d.reconstructionGapMm));
          ray.d = Vec3(-frame.up(top));
          for (const MlaModel* m : {static_cast<const MlaModel*>(&real), static_cast<const MlaModel*>(&ideal)}) {
            PanelArrival a;
            ASSERT_TRUE(m->traceToPanel(ray, 550.0f, FresnelMode::Off, nullptr, a)) << k << ", " << l;
            EXPECT_NEAR(a.p.x, fx, 2e-4) << k << ", " << l;
            EXPECT_NEAR(a.p.y, fy, 2e-4) << k << ", " << l;
            EXPECT_EQ(a.lensletK, k);
            EXPECT_EQ(a.lensletL, l);
          }
        }
      if (lattice == Mla::Lattice::Hex) {  // every pixel on the EI of the lens nearest its projection
        int k, l;
        ASSERT_TRUE(L.eiAtPixel(L.eiaW / 2, L.eiaH / 2, k, l));
        EXPECT_LT(std::hypot(L.eiCentreXAt(k, l) - L.pixelCentreX(L.eiaW / 2), L.eiCentreYAt(k, l) - L.pixelCentreY(L.eiaH / 2)),
                  0.6);
      }
    }
}
