// Real ray tracing through sequential surfaces: Snell, conic intersections, the lensmaker
// equation, a stigmatic conic, vignetting and total internal reflection.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/lens_analysis.h"
#include "camera/lens_focus.h"
#include "camera/lens_loader.h"
#include "camera/lens_system.h"
#include "camera_test_util.h"

using namespace inim;
using inim::test::singlet;

TEST(LensSystem, SnellInvariantAtEveryRefraction) {
  // Skew rays through the double Gauss: n sin(theta) is the same on both sides of every
  // refracting surface and the refracted ray stays in the plane of incidence.
  LensSystem lens = loadLens("dgauss.50mm");
  int refractions = 0;
  for (double hx : {0.0, 3.0, -5.5})
    for (double hy : {0.5, 4.0, 7.0})
      for (double ang : {0.0, 0.1, -0.2}) {
        LensRay r{{hx, hy, -5.0}, glm::normalize(Vec3d(ang, 0.5 * ang, 1.0))};
        std::vector<SurfaceHit> path;
        TraceResult tr = lens.trace(r, 587.56, TraceDirection::ObjectToImage, {}, &path);
        for (const auto& h : path) {
          if (h.nIn == h.nOut) continue;
          ++refractions;
          const double sIn = h.nIn * glm::length(glm::cross(h.dIn, h.normal));
          const double sOut = h.nOut * glm::length(glm::cross(h.dOut, h.normal));
          EXPECT_NEAR(sIn, sOut, 1e-12) << "surface " << h.surface;
          EXPECT_NEAR(glm::dot(h.dOut, glm::cross(h.dIn, h.normal)), 0.0, 1e-12);
          EXPECT_NEAR(glm::length(h.dOut), 1.0, 1e-14);
          EXPECT_GT(glm::dot(h.dOut, h.dIn), 0.0);  // refracted, not reflected
        }
        if (tr.ok()) {
          EXPECT_EQ(int(path.size()), lens.surfaceCount());
        }
      }
  EXPECT_GT(refractions, 100);
}

TEST(LensSystem, ConicIntersectionLiesOnTheSag) {
  for (double k : {0.0, -0.5, -1.0, -2.25, 0.8})
    for (double R : {25.0, -40.0}) {
      const double c = 1.0 / R;
      for (double y : {0.0, 1.0, 4.0, 7.5}) {
        const Vec3d o(0.3, y, -10.0), d = glm::normalize(Vec3d(0.01, -0.02, 1.0));
        const double t = intersectConic(o, d, c, k);
        ASSERT_GT(t, 0.0) << "k " << k << " R " << R << " y " << y;
        const Vec3d p = o + t * d;
        const double r2 = p.x * p.x + p.y * p.y;
        const double sag = c * r2 / (1.0 + std::sqrt(1.0 - (1.0 + k) * c * c * r2));
        EXPECT_NEAR(p.z, sag, 1e-12);
        // The normal is the gradient direction of F = c (r^2 + (1+k) z^2) - 2 z.
        const Vec3d n = conicNormal(p, c, k);
        const double eps = 1e-6;
        const double dz = (c * (std::pow(p.x + eps, 2) + p.y * p.y) / (1.0 + std::sqrt(1.0 - (1.0 + k) * c * c * (std::pow(p.x + eps, 2) + p.y * p.y))) - sag) / eps;
        EXPECT_NEAR(n.x / -n.z, dz, 1e-5);  // n ~ (dsag/dx, dsag/dy, -1)
      }
    }
}

TEST(LensSystem, ThickBiconvexMatchesLensmaker) {
  // Thick-lens lensmaker: 1/f = (n-1) [1/R1 - 1/R2 + (n-1) d / (n R1 R2)],
  // BFL = f (1 - (n-1) d / (n R1)), FFL = f (1 + (n-1) d / (n R2)).
  struct Case { double r1, r2, d, n; };
  for (const Case& c : {Case{50.0, -40.0, 8.0, 1.5168}, Case{30.0, 0.0, 5.0, 1.7}, Case{20.0, 60.0, 4.0, 1.6}}) {
    LensSystem lens = singlet(c.r1, c.r2, c.d, c.n, 12.0);
    const double n = double(float(c.n));
    const double inv2 = c.r2 == 0.0 ? 0.0 : 1.0 / c.r2;
    const double power = (n - 1.0) * (1.0 / c.r1 - inv2 + (n - 1.0) * c.d * (1.0 / c.r1) * inv2 / n);
    const double f = 1.0 / power;
    const double bfl = f * (1.0 - (n - 1.0) * c.d / (n * c.r1));
    const double ffl = f * (1.0 + (n - 1.0) * c.d * inv2 / n);
    LensInfo info = analyzeLens(lens);
    EXPECT_NEAR(info.eflMm / f, 1.0, 1e-4) << "R1 " << c.r1 << " R2 " << c.r2;
    EXPECT_NEAR(info.bflMm / bfl, 1.0, 1e-4);
    EXPECT_NEAR(info.fflMm / ffl, 1.0, 1e-4);
    // Much tighter in fact: the extrapolated real trace is the paraxial value.
    EXPECT_NEAR(info.eflMm / f, 1.0, 1e-8);
    // Stop at the first vertex: the entrance pupil is the stop.
    EXPECT_NEAR(info.entrancePupil.positionMm, 0.0, 1e-12);
    EXPECT_NEAR(info.entrancePupil.diameterMm, 12.0, 1e-9);
    EXPECT_NEAR(info.fNumber, f / 12.0, 1e-8);
  }
}

TEST(LensSystem, PlanoHyperbolicLensIsStigmatic) {
  // Collimated light entering the flat side of a plano-convex lens whose convex side is a
  // hyperboloid with k = -n^2 focuses to a perfect point; the spherical version does not.
  const double n = 1.5, R = -20.0;
  LensSystem hyper = singlet(0.0, R, 5.0, n, 16.0, 0.0, -n * n);
  LensSystem sphere = singlet(0.0, R, 5.0, n, 16.0);
  const double f = -R / (double(float(n)) - 1.0);
  LensInfo hi = analyzeLens(hyper);
  EXPECT_NEAR(hi.eflMm, f, 1e-9);
  EXPECT_NEAR(hi.bflMm, f, 1e-9);  // the principal plane is at the curved vertex
  SpotDiagram sh = spotDiagramAtInfinity(hyper, {0, 0, 1}, hi.bflMm, 587.56, 41);
  SpotDiagram ss = spotDiagramAtInfinity(sphere, {0, 0, 1}, analyzeLens(sphere).bflMm, 587.56, 41);
  EXPECT_GT(sh.rays, 500);
  EXPECT_LT(sh.rmsRadiusMm, 1e-9);
  EXPECT_GT(ss.rmsRadiusMm, 1e-2);  // spherical aberration at f/2.5
  RecordProperty("hyperbolic_rms_mm", std::to_string(sh.rmsRadiusMm));
  RecordProperty("spherical_rms_mm", std::to_string(ss.rmsRadiusMm));
}

TEST(LensSystem, VignettingMissesAndTirBlockWithoutNaN) {
  LensSystem lens = singlet(30.0, -30.0, 6.0, 1.8, 20.0);
  // Outside the clear aperture of the first real surface.
  LensRay r{{0.0, 10.5, -5.0}, {0.0, 0.0, 1.0}};
  TraceResult a = lens.trace(r, 550.0, TraceDirection::ObjectToImage);
  EXPECT_EQ(a.status, TraceStatus::Aperture);
  // Without apertures the same ray goes through.
  TraceOptions noAp;
  noAp.apertures = false;
  r = {{0.0, 9.0, -5.0}, {0.0, 0.0, 1.0}};
  EXPECT_TRUE(lens.trace(r, 550.0, TraceDirection::ObjectToImage, noAp).ok());
  // A ray that misses the sphere entirely (beyond its radius).
  r = {{0.0, 31.0, -5.0}, {0.0, 0.0, 1.0}};
  TraceResult m = lens.trace(r, 550.0, TraceDirection::ObjectToImage, noAp);
  EXPECT_EQ(m.status, TraceStatus::Missed);
  // Grazing: tangent to the sphere (discriminant 0) must not produce NaN.
  r = {{0.0, 30.0, -5.0}, {0.0, 0.0, 1.0}};
  TraceResult g = lens.trace(r, 550.0, TraceDirection::ObjectToImage, noAp);
  if (g.ok()) {
    EXPECT_TRUE(std::isfinite(r.d.x) && std::isfinite(r.d.y) && std::isfinite(r.d.z));
  }
  // Total internal reflection at the back surface for a steep ray inside the glass.
  Vec3d out;
  EXPECT_FALSE(snellRefract(glm::normalize(Vec3d(0.0, 0.8, 0.6)), {0.0, 0.0, -1.0}, 1.8, 1.0, out));
  EXPECT_NEAR(fresnelTransmittance(0.6, 1.8, 1.0), 0.0, 0.0);
  // Through the lens: a steep ray from inside hits the rear surface beyond the critical angle.
  LensRay steep{{0.0, -9.0, 1.5}, glm::normalize(Vec3d(0.0, 1.0, 0.25))};
  TraceResult t = lens.trace(steep, 550.0, TraceDirection::ObjectToImage, [] {
    TraceOptions x;
    x.apertures = false;
    x.first = 2;
    return x;
  }());
  EXPECT_EQ(t.status, TraceStatus::TotalInternalReflection);
}

TEST(LensSystem, FresnelTransmittanceNormalIncidence) {
  // T = 1 - ((n1 - n2) / (n1 + n2))^2 at normal incidence; R + T = 1 by construction.
  EXPECT_NEAR(fresnelTransmittance(1.0, 1.0, 1.5), 1.0 - 0.04, 1e-12);
  LensSystem lens = singlet(0.0, 0.0, 5.0, 1.5, 10.0);
  LensRay r{{0.0, 1.0, -1.0}, {0.0, 0.0, 1.0}};
  TraceOptions o;
  o.fresnel = true;
  TraceResult tr = lens.trace(r, 550.0, TraceDirection::ObjectToImage, o);
  ASSERT_TRUE(tr.ok());
  EXPECT_NEAR(tr.transmittance, 0.96 * 0.96, 1e-6);
}

TEST(LensSystem, ForwardAndBackwardTracesRetrace) {
  // A ray traced object -> image and then reversed retraces its path (reciprocity).
  LensSystem lens = loadLens("dgauss.50mm");
  LensRay r{{1.0, 3.0, -20.0}, glm::normalize(Vec3d(-0.02, 0.05, 1.0))};
  const Point3d start = r.o;
  ASSERT_TRUE(lens.trace(r, 587.56, TraceDirection::ObjectToImage).ok());
  LensRay back{r.o + 10.0 * r.d, -r.d};
  ASSERT_TRUE(lens.trace(back, 587.56, TraceDirection::ImageToObject).ok());
  // Back at z = -20 the reversed ray passes through the start point.
  const double t = (start.z - back.o.z) / back.d.z;
  const Point3d p = back.o + t * back.d;
  EXPECT_NEAR(p.x, start.x, 1e-9);
  EXPECT_NEAR(p.y, start.y, 1e-9);
}
