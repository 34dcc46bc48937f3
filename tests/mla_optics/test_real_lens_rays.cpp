// Real-lens display rays: the chief ray through the lenslet's aperture centre and the centroid of
// the pixel's exit bundle, against the pinhole model and paraxial thick-lens theory.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "fixtures.h"
#include "core/parallel.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/real_lens_rays.h"
#include "mla_test_util.h"

using namespace inim;
using namespace mla_test;

namespace {

double thetaDeg(const Vec3d& d) { return std::atan2(std::hypot(d.x, d.y), d.z) * 180.0 / M_PI; }

RealLensRayOptions opts(RealLensRayModel m, int n = 8) {
  RealLensRayOptions o;
  o.model = m;
  o.samplesPerAxis = n;
  return o;
}

}  // namespace

// The chief ray passes through the cap vertex (the aperture centre) and is reversible: traced
// back from the viewer it lands on the pixel centre.
TEST(RealLensRays, ChiefRayThroughApertureCentreIsReversible) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const Point3d c = mla->lensletCentre(5, 5);
    for (double dx : {0.0, 0.05, 0.4, 1.2, -1.44}) {
      const Point3d pixel(c.x + dx, c.y - 0.3 * dx, mla->panelZ());
      const RealLensRay r = realLensRay(*mla, pixel, 5, 5, opts(RealLensRayModel::Chief));
      ASSERT_TRUE(r.real);
      EXPECT_EQ(r.exitK, 5);
      EXPECT_EQ(r.o.z, 0.0);
      EXPECT_GT(r.d.z, 0.0);
      // Backward from 5 mm in front of the reference plane.
      MlaTraceLog log;
      MlaExit ex;
      ASSERT_TRUE(mla->trace(r.o + 5.0 / r.d.z * r.d, -r.d, kLambdaDNm, FresnelMode::Off, nullptr, ex, &log));
      const double t = (mla->panelZ() - ex.p.z) / ex.d.z;
      const Point3d land = ex.p + t * ex.d;
      EXPECT_NEAR(land.x, pixel.x, 1e-9);
      EXPECT_NEAR(land.y, pixel.y, 1e-9);
      bool throughVertex = false;
      for (auto& e : log.events)
        if (e.surface == MlaTraceEvent::Surface::Cap)
          throughVertex = std::hypot(e.p.x - c.x, e.p.y - c.y) < 1e-9 && std::abs(e.p.z - mla->vertexZ()) < 1e-9;
      EXPECT_TRUE(throughVertex) << orientationName(o) << " dx = " << dx;
    }
  }
}

// Paraxial agreement with the pinhole model. The chief ray's direction differs from the pinhole
// ray's by a third-order term (curved toward viewer: the plate of thickness T between the two
// nodal points) or not at all (curved toward panel, H at the vertex).
TEST(RealLensRays, ChiefRayAgreesWithPinholeParaxially) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const Point3d c = mla->lensletCentre(5, 5);
    double prev = 0.0, prevDx = 0.0;
    for (double dx : {0.32, 0.16, 0.08, 0.04, 0.02, 0.01}) {
      const Point3d pixel(c.x + dx, c.y + 0.5 * dx, mla->panelZ());
      const Vec3d pin = unit(c - pixel);
      const RealLensRay r = realLensRay(*mla, pixel, 5, 5, opts(RealLensRayModel::Chief));
      const double dev = angle(r.d, pin);
      std::printf("  %s chief: offset %.3f mm, pinhole %.4f deg, real %.4f deg, difference %.2e rad\n",
                  orientationName(o), dx * std::sqrt(1.25), thetaDeg(pin), thetaDeg(r.d), dev);
      if (o == kPanel) {
        EXPECT_LT(dev, 1e-14);
      } else if (prev > 0.0) {
        EXPECT_NEAR(prev / dev, std::pow(prevDx / dx, 3), 1.0);  // ~ 8
      }
      prev = dev, prevDx = dx;
    }
    EXPECT_LT(prev, 1e-8);  // 0.01 mm offset (0.2 deg): 10 nrad
  }
}

// The centroid of the exit bundle approaches paraxial thick-lens theory: a point on the panel
// at offset d from the lenslet axis, g = f in front of H, sends a collimated beam at
// tan(theta) = d / g (the nodal ray's direction). With a shrinking aperture (circular, radius
// a) the relative error of the centroid falls like a^2 (third-order coma); at the full
// aperture it stays a fixed fraction of the angle (a real aberration, stated below).
TEST(RealLensRays, CentroidApproachesParaxialTheory) {
  for (auto o : {kViewer, kPanel}) {
    const double dx = 0.02;  // small: the field's own third-order term stays below 1e-5
    double prev = 0.0;
    for (double a : {0.8, 0.4, 0.2, 0.1}) {
      Spec s = spec(o);
      s.aperture = Mla::Aperture::Circle;
      s.aperture_mm = a;
      s.gap = 1.62 / (pmma()->n(float(kLambdaDNm)) - 1.0);  // g = f: the panel in the focal plane
      auto mla = makeMla(s);
      const Point3d c = mla->lensletCentre(5, 5);
      const Point3d pixel(c.x + dx, c.y, mla->panelZ());
      const RealLensRay r = realLensRay(*mla, pixel, 5, 5, opts(RealLensRayModel::Centroid, 16));
      ASSERT_TRUE(r.real);
      const double tanParaxial = dx / s.gap, tanReal = std::abs(r.d.x / r.d.z);
      const double rel = std::abs(tanReal / tanParaxial - 1.0);
      std::printf("  %s centroid, aperture %.1f mm: tan(theta) %.7f vs paraxial d/g %.7f: relative %.2e\n",
                  orientationName(o), a, tanReal, tanParaxial, rel);
      if (prev > 0.0) {
        EXPECT_GT(prev / rel, 3.0);  // ~ 4 per halving of the aperture
        EXPECT_LT(prev / rel, 5.0);
      }
      prev = rel;
    }
    EXPECT_LT(prev, 5e-4);  // 0.1 mm aperture: paraxial within 0.05 %
  }
}

// At the full aperture of the prototype MLA (g = f = 3.3 mm), the centroid differs from the
// pinhole ray by less than 1.2 % of the angle (curved toward viewer, measured 0.94 %) or 4.5 %
// (curved toward panel, measured 4.0 %); the difference vanishes (linearly) with the offset.
TEST(RealLensRays, CentroidNearAxisAtFullAperture) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const Point3d c = mla->lensletCentre(5, 5);
    const RealLensRay axis = realLensRay(*mla, Point3d(c.x, c.y, mla->panelZ()), 5, 5, opts(RealLensRayModel::Centroid));
    EXPECT_LT(angle(axis.d, Vec3d(0, 0, 1)), 1e-15);
    EXPECT_LT(std::hypot(axis.o.x - c.x, axis.o.y - c.y), 1e-12);
    double prevDev = 1.0;
    for (double dx : {0.32, 0.16, 0.08, 0.04, 0.02, 0.01}) {
      const Point3d pixel(c.x + dx, c.y, mla->panelZ());
      const double thPin = std::atan(dx / 3.3);
      const RealLensRay r = realLensRay(*mla, pixel, 5, 5, opts(RealLensRayModel::Centroid));
      const double th = std::atan2(-r.d.x, r.d.z);
      const double rel = th / thPin - 1.0;
      std::printf("  %s centroid: offset %.2f mm, pinhole %.4f deg, centroid %.4f deg (%+.2f %%)\n", orientationName(o),
                  dx, thPin * 180 / M_PI, th * 180 / M_PI, 100 * rel);
      EXPECT_LT(std::abs(rel), o == kViewer ? 0.012 : 0.045);
      EXPECT_LT(std::abs(th - thPin), prevDev);
      prevDev = std::abs(th - thPin);
    }
    EXPECT_LT(prevDev, 2e-4);  // 0.01 mm: below 0.2 mrad
  }
}

// The table of pixel offsets that generateRealLensRays uses matches the direct centroid.
TEST(RealLensRays, OffsetTableMatchesDirectComputation) {
  for (auto [o, model] : std::vector<std::pair<Mla::Orientation, RealLensRayModel>>{
           {kViewer, RealLensRayModel::Centroid},
           {kPanel, RealLensRayModel::Centroid},
           {kViewer, RealLensRayModel::Chief}}) {
    Display d = fixtures::paperDisplay({.cols = 5, .rows = 3, .layout = EiLayoutKind::Parallel});
    d.mla.orientation = o;
    EiLayout L = computeLayout(d);
    auto mla = RealMla::fromDisplay(d, L, L.gapMm);
    RealLensRayOptions tab = opts(model), direct = tab;
    direct.tableStepMm = 0.0;
    RealLensRayStats st1, st2;
    RaySet a = generateRealLensRays(L, *mla, tab, &st1);
    RaySet b = generateRealLensRays(L, *mla, direct, &st2);
    ASSERT_EQ(a.size(), size_t(L.numRays()));
    double worstAngle = 0.0, worstO = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      worstAngle = std::max(worstAngle, angle(unit(Vec3d(a.ray(i).d)), unit(Vec3d(b.ray(i).d))));
      worstO = std::max(worstO, norm(Vec3d(a.ray(i).o) - Vec3d(b.ray(i).o)));
    }
    std::printf("  %s, %s: table vs direct over %zu rays: worst %.2e rad, origin %.2e mm; %.2f s vs %.2f s\n",
                orientationName(o), realLensRayModelName(model), a.size(), worstAngle, worstO, st1.seconds,
                st2.seconds);
    EXPECT_LT(worstAngle, 1e-6);
    EXPECT_LT(worstO, 1e-5);
    EXPECT_EQ(st1.fallback, 0u);
  }
}

// Whole layouts: ray order, origins on z = 0, directions toward the viewer, close to the pinhole
// rays through the same (physical) lens centres, identical for 1 and 2 threads.
TEST(RealLensRays, LayoutRaysDeterministicAndNearPinhole) {
  Display d = fixtures::paperDisplay({.cols = 9, .rows = 5, .layout = EiLayoutKind::LensGrid});
  EiLayout L = computeLayout(d);
  auto mla = RealMla::fromDisplay(d, L, L.gapMm);
  for (auto model : {RealLensRayModel::Chief, RealLensRayModel::Centroid}) {
    RaySet one, two;
    RealLensRayStats st;
    {
      ThreadLimit t(1);
      one = generateRealLensRays(L, *mla, opts(model), &st);
    }
    {
      ThreadLimit t(2);
      two = generateRealLensRays(L, *mla, opts(model));
    }
    ASSERT_EQ(one.size(), size_t(L.numRays()));
    EXPECT_EQ(one.dx, two.dx);
    EXPECT_EQ(one.ox, two.ox);
    EXPECT_EQ(one.oy, two.oy);
    EXPECT_EQ(st.fallback, 0u);
    EXPECT_EQ(st.crosstalk, 0u);
    double worst = 0.0;
    for (int64_t r = 0; r < L.numRays(); ++r) {
      // The pinhole ray (lens-grid: pinhole = lens centre) of the same index, as rays/ does it.
      const int64_t e = r / L.raysPerEi(), inEi = r % L.raysPerEi();
      const int k = int(e / L.eiRows), l = L.eiRows - 1 - int(e % L.eiRows);
      const int i = int(inEi / L.eiH), jb = int(inEi % L.eiH);
      const Point3d pixel(L.pixelCentreX(L.eiCol0[size_t(k)] + i), L.pixelCentreY(L.eiRow0[size_t(l)] + L.eiH - 1 - jb),
                          -L.gapMm);
      const Vec3d pin = unit(Point3d(L.pinholeX[size_t(k)], L.pinholeY[size_t(l)], 0.0) - pixel);
      const Ray ray = one.ray(size_t(r));
      ASSERT_EQ(ray.o.z, 0.0f);
      ASSERT_GT(ray.d.z, 0.0f);
      EXPECT_NEAR(glm::length(ray.d), 1.0f, 1e-6f);
      worst = std::max(worst, angle(unit(Vec3d(ray.d)), pin));
      EXPECT_NEAR(ray.o.x, L.pinholeX[size_t(k)], 0.15);  // the rear nodal point's shift
    }
    std::printf("  %s: %lld rays, largest angle to the pinhole ray %.3f deg (mean %.4f deg)\n",
                realLensRayModelName(model), (long long)L.numRays(), worst * 180 / M_PI, st.meanDeviationDeg);
    EXPECT_LT(worst * 180 / M_PI, model == RealLensRayModel::Chief ? 0.1 : 0.3);
  }
}

// EI corner pixels at the largest angles: the prototype's parallel layout puts the corner EIs'
// pixels up to 1.44 mm from their physical lens centres (24 degrees at g = 3.3 mm).
TEST(RealLensRays, EiCornerPixelsAtLargestAngles) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  auto mla = RealMla::fromDisplay(d, L, L.gapMm);
  double largest = 0.0;
  for (int k : {0, L.eiCols - 1})
    for (int l : {0, L.eiRows - 1})
      for (int i : {0, L.eiW - 1})
        for (int j : {0, L.eiH - 1}) {
          const Point3d pixel(L.pixelCentreX(L.eiCol0[size_t(k)] + i), L.pixelCentreY(L.eiRow0[size_t(l)] + j), -L.gapMm);
          const Point3d c = mla->lensletCentre(k, l);
          const Vec3d pin = unit(c - pixel);
          for (auto model : {RealLensRayModel::Chief, RealLensRayModel::Centroid}) {
            for (double lambda : {450.0, kLambdaDNm, 650.0}) {
              RealLensRayOptions o = opts(model);
              o.wavelengthNm = lambda;
              const RealLensRay r = realLensRay(*mla, pixel, k, l, o);
              ASSERT_TRUE(r.real) << k << "," << l << " px " << i << "," << j;
              EXPECT_TRUE(finite(r.o) && finite(r.d));
              EXPECT_GT(r.d.z, 0.0);
              EXPECT_LT(angle(r.d, pin) * 180 / M_PI, 1.5);
              largest = std::max(largest, thetaDeg(r.d));
            }
          }
        }
  std::printf("  largest corner-pixel angle %.2f deg\n", largest);
  EXPECT_GT(largest, 20.0);
}

// The prototype's full layout (6.2 M rays), centroid model: no fallbacks; time reported.
TEST(RealLensRays, PrototypeFullLayout) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  auto mla = RealMla::fromDisplay(d, L, L.gapMm);
  for (auto model : {RealLensRayModel::Centroid, RealLensRayModel::Chief}) {
    RealLensRayStats st;
    RaySet rays = generateRealLensRays(L, *mla, opts(model), &st);
    ASSERT_EQ(rays.size(), size_t(L.numRays()));
    std::printf("  %s: %llu rays in %.2f s; %llu fallbacks, %llu crosstalk; vs pinhole rays through the lens "
                "centres: max %.3f deg, mean %.4f deg\n",
                realLensRayModelName(model), (unsigned long long)st.rays, st.seconds,
                (unsigned long long)st.fallback, (unsigned long long)st.crosstalk, st.maxDeviationDeg,
                st.meanDeviationDeg);
    EXPECT_EQ(st.fallback, 0u);
    EXPECT_LT(st.maxDeviationDeg, 1.5);
  }
}
