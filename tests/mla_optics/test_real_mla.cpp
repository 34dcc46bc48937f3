// RealMla against analytic references: paraxial focal length and back focal distance of a
// plano-convex lenslet (both orientations, both lattices, several wavelengths), the reference
// plane (nodal points), Snell's invariant at every interface, Fresnel energy, TIR, absorption,
// and the hard cases: rays on lenslet edges and corners, grazing and parallel rays, crosstalk.
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

#include "core/error.h"
#include "mla_test_util.h"

using namespace inim;
using namespace mla_test;

namespace {

// Collimated rays from the viewer at height h above lenslet (k, l)'s axis: the traced EFL
// h / tan(u') and where the ray crosses the axis.
struct FocusResult {
  double efl = 0.0, zAxis = 0.0;
};
FocusResult collimatedFromViewer(const RealMla& mla, int k, int l, double h, double lambda) {
  const Point3d c = mla.lensletCentre(k, l);
  MlaExit ex;
  EXPECT_TRUE(mla.trace({c.x + h, c.y, mla.frontZ() + 1.0}, {0, 0, -1}, lambda, FresnelMode::Off, nullptr, ex));
  EXPECT_LT(ex.d.z, 0.0);
  FocusResult r;
  r.efl = h * std::abs(ex.d.z / ex.d.x);
  r.zAxis = ex.p.z + (c.x - ex.p.x) * ex.d.z / ex.d.x;
  return r;
}
FocusResult collimatedFromPanel(const RealMla& mla, int k, int l, double h, double lambda) {
  const Point3d c = mla.lensletCentre(k, l);
  MlaExit ex;
  EXPECT_TRUE(mla.traceToViewer({c.x + h, c.y, mla.panelZ()}, {0, 0, 1}, lambda, nullptr, ex));
  FocusResult r;
  r.efl = h * std::abs(ex.d.z / ex.d.x);
  r.zAxis = ex.p.z + (c.x - ex.p.x) * ex.d.z / ex.d.x;
  return r;
}

}  // namespace

// f = R / (n - 1) within 0.5 % from a traced paraxial ray (h = 5 um), both orientations.
TEST(RealMla, ParaxialFocalLengthPlanoConvex) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const double n = mla->n(kLambdaDNm), f = 1.62 / (n - 1.0);
    FocusResult a = collimatedFromViewer(*mla, 5, 5, 0.005, kLambdaDNm);
    FocusResult b = collimatedFromPanel(*mla, 5, 5, 0.005, kLambdaDNm);
    std::printf("  %s: n_d = %.6f, R/(n-1) = %.6f mm, traced EFL from viewer %.6f mm, from panel %.6f mm\n",
                orientationName(o), n, f, a.efl, b.efl);
    EXPECT_NEAR(a.efl, f, 0.005 * f);
    EXPECT_NEAR(b.efl, f, 0.005 * f);
    EXPECT_NEAR(a.efl, f, 1e-4 * f);  // in fact much closer: (h/R)^2 ~ 1e-5
    EXPECT_NEAR(mla->focalLength(kLambdaDNm), f, 1e-12);
  }
}

// Parallel rays focus at the thick-lens back focal distance: collimated light through the
// curved face first focuses BFL = f - T/n behind the flat face; through the flat face first,
// f behind the vertex.
TEST(RealMla, CollimatedRaysFocusAtBackFocalDistance) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const double n = mla->n(kLambdaDNm), f = 1.62 / (n - 1.0), T = 1.5;
    // h = 1 um: the sphere's longitudinal aberration (0.29 mm at h = 0.45 mm) is 1.4e-6 mm.
    FocusResult a = collimatedFromViewer(*mla, 5, 5, 0.001, kLambdaDNm);
    FocusResult b = collimatedFromPanel(*mla, 5, 5, 0.001, kLambdaDNm);
    double bflViewer, bflPanel;  // measured from the MLA's last surface
    if (o == kViewer) {
      bflViewer = mla->flatZ() - a.zAxis;   // cap first, flat last
      bflPanel = b.zAxis - mla->vertexZ();  // flat first, cap last
      EXPECT_NEAR(bflViewer, f - T / n, 5e-6);
      EXPECT_NEAR(bflPanel, f, 5e-6);
    } else {
      bflViewer = mla->vertexZ() - a.zAxis;  // flat first, cap last
      bflPanel = b.zAxis - mla->flatZ();     // cap first, flat last
      EXPECT_NEAR(bflViewer, f, 5e-6);
      EXPECT_NEAR(bflPanel, f - T / n, 5e-6);
    }
    std::printf("  %s: BFL toward panel %.6f mm, toward viewer %.6f mm (f = %.6f, f - T/n = %.6f)\n",
                orientationName(o), bflViewer, bflPanel, f, f - T / n);
    EXPECT_NEAR(a.zAxis, mla->frontFocalZ(kLambdaDNm), 5e-6);
    EXPECT_NEAR(b.zAxis, mla->rearFocalZ(kLambdaDNm), 5e-6);
    // The reference plane holds H: the panel-side focal point is at z = -f (n_d placed the
    // MLA; n(587.56) from the 1 nm table differs from it by ~5e-8).
    EXPECT_NEAR(mla->frontFocalZ(kLambdaDNm), -f, 1e-6);
    EXPECT_NEAR(mla->rearFocalZ(kLambdaDNm), mla->rearNodalZ() + f, 1e-6);
  }
}

// A hyperboloid cap with conic -n^2, reached from inside the glass by collimated light (flat face
// first), is free of spherical aberration: marginal rays focus with the paraxial ones. The
// sphere has clear spherical aberration. Checks the conic cap.
TEST(RealMla, HyperbolicConicCapIsAplanaticOnAxis) {
  Spec s = spec(kPanel);
  const double nd = pmma()->n(float(kLambdaDNm));
  s.conic = -nd * nd;
  auto hyper = makeMla(s);
  auto sphere = makeMla(spec(kPanel));
  const double zPar = collimatedFromViewer(*hyper, 5, 5, 0.0005, kLambdaDNm).zAxis;
  const double zMarg = collimatedFromViewer(*hyper, 5, 5, 0.45, kLambdaDNm).zAxis;
  const double sPar = collimatedFromViewer(*sphere, 5, 5, 0.0005, kLambdaDNm).zAxis;
  const double sMarg = collimatedFromViewer(*sphere, 5, 5, 0.45, kLambdaDNm).zAxis;
  std::printf("  longitudinal SA at h = 0.45 mm: hyperboloid %.2e mm, sphere %.4f mm\n", zMarg - zPar, sMarg - sPar);
  EXPECT_NEAR(zMarg, zPar, 1e-6);  // n(587.56) from the table vs n_d in the conic: 5e-8
  EXPECT_GT(std::abs(sMarg - sPar), 0.05);
  EXPECT_NEAR(zPar, sPar, 1e-6);  // same vertex radius: same paraxial focus
}

// Dispersion: f(450 nm) < f(650 nm) because n(450) > n(650), each within 0.5 % of R/(n(l) - 1).
TEST(RealMla, DispersionOrdersFocalLengths) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    EXPECT_TRUE(mla->isDispersive());
    const double n450 = mla->n(450), n650 = mla->n(650);
    ASSERT_GT(n450, n650);
    const double f450 = collimatedFromViewer(*mla, 5, 5, 0.005, 450).efl;
    const double f650 = collimatedFromViewer(*mla, 5, 5, 0.005, 650).efl;
    std::printf("  %s: n(450) = %.5f, n(650) = %.5f; traced f(450) = %.5f mm, f(650) = %.5f mm\n",
                orientationName(o), n450, n650, f450, f650);
    EXPECT_LT(f450, f650);
    EXPECT_NEAR(f450, 1.62 / (n450 - 1), 0.005 * f450);
    EXPECT_NEAR(f650, 1.62 / (n650 - 1), 0.005 * f650);
    EXPECT_NEAR(mla->n(450), double(pmma()->n(450.0f)), 1e-6);
  }
}

// Hex lattice with hex apertures, and circular apertures: the paraxial focal length of any
// lenslet (here an off-centre one) is R / (n - 1).
TEST(RealMla, HexLatticeAndCircularAperturesFocus) {
  for (auto o : {kViewer, kPanel}) {
    Spec h = spec(o);
    h.lattice = Mla::Lattice::Hex;
    h.aperture = Mla::Aperture::Hex;
    Spec c = spec(o);
    c.aperture = Mla::Aperture::Circle;
    for (const Spec& s : {h, c}) {
      auto mla = makeMla(s);
      const double f = 1.62 / (mla->n(kLambdaDNm) - 1.0);
      FocusResult a = collimatedFromViewer(*mla, 7, 4, 0.005, kLambdaDNm);
      EXPECT_NEAR(a.efl, f, 0.005 * f) << latticeName(s.lattice) << " " << apertureName(s.aperture);
      EXPECT_NEAR(a.zAxis, mla->frontFocalZ(kLambdaDNm), 5e-5);  // h = 5 um: SA 3.6e-5
    }
  }
  // Hex geometry: neighbours at distance P in 6 directions, cells found by nearest centre.
  Spec h;
  h.lattice = Mla::Lattice::Hex;
  h.aperture = Mla::Aperture::Hex;
  auto mla = makeMla(h);
  const Point3d c = mla->lensletCentre(5, 5);
  EXPECT_NEAR(c.x, 0.0, 1e-12);
  EXPECT_NEAR(c.y, 0.0, 1e-12);
  for (auto [k, l] : std::vector<std::pair<int, int>>{{4, 5}, {6, 5}, {5, 4}, {6, 4}, {5, 6}, {6, 6}}) {
    const Point3d q = mla->lensletCentre(k, l);
    EXPECT_NEAR(std::hypot(q.x - c.x, q.y - c.y), 1.0, 1e-12) << k << "," << l;
    int kk, ll;
    mla->cellAt(q.x + 0.1, q.y - 0.2, kk, ll);
    EXPECT_EQ(kk, k);
    EXPECT_EQ(ll, l);
  }
}

// Reference plane (docs/design.md): the panel-side nodal point of every lenslet is on
// z = 0. A ray from a panel point aimed at (x_c, y_c, 0) leaves parallel to itself (the
// pinhole ray's direction), with a difference that vanishes like the cube of the offset, and
// its exit line crosses the axis at the rear nodal point z = T (n - 1)/n.
TEST(RealMla, ReferencePlanePinholeRayIsTheParaxialChiefRay) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const Point3d c = mla->lensletCentre(5, 5);
    const double g = 3.3, n = mla->n(kLambdaDNm), T = 1.5;
    const double nr = mla->referenceIndex();
    EXPECT_NEAR(nr, n, 1e-6);
    EXPECT_NEAR(mla->rearNodalZ(), T * (nr - 1.0) / nr, 1e-15);
    double prev = 0.0;
    for (double delta : {0.2, 0.1, 0.05, 0.025, 0.0125}) {
      const Point3d pixel(c.x + delta, c.y + 0.5 * delta, -g);
      const Vec3d pin = unit(c - pixel);  // the pinhole ray
      MlaExit ex;
      ASSERT_TRUE(mla->traceToViewer(pixel, pin, kLambdaDNm, nullptr, ex));
      const double dev = angle(ex.d, pin);
      // Where the exit line passes the lenslet axis (closest approach along x).
      const double zc = ex.p.z + (c.x - ex.p.x) * ex.d.z / ex.d.x;
      std::printf("  %s: offset %.4f mm (%.3f deg): exit vs pinhole %.3e rad, axis crossing z = %.6f (N' = %.6f)\n",
                  orientationName(o), delta * std::sqrt(1.25), std::atan(delta * std::sqrt(1.25) / g) * 180 / M_PI,
                  dev, zc, mla->rearNodalZ());
      if (o == kPanel) {
        // The ray through H = the cap vertex meets two surfaces normal to the axis: it leaves
        // exactly parallel to itself at any angle.
        EXPECT_LT(dev, 1e-14);
      } else if (prev > 0.0) {
        EXPECT_GT(prev / dev, 6.0);  // ~ 8: third order in the offset
        EXPECT_LT(prev / dev, 10.0);
      }
      prev = dev;
      EXPECT_NEAR(zc, mla->rearNodalZ(), 0.05 * delta * delta + 1e-9);  // 0.032 delta^2 measured
    }
    EXPECT_LT(prev, 1e-8);  // at 0.014 mm (0.24 deg) the directions agree to 0.01 urad
  }
}

// Snell's invariant n sin(theta) and coplanarity at every refraction, the law of reflection at
// every reflection, over random rays through all lattice / aperture / orientation variants.
TEST(RealMla, SnellInvariantAtEveryInterface) {
  std::vector<Spec> specs;
  for (auto o : {kViewer, kPanel}) {
    Spec a = spec(o);
    specs.push_back(a);
    a.aperture = Mla::Aperture::Circle;
    specs.push_back(a);
    a.aperture = Mla::Aperture::Square;
    a.aperture_mm = 0.8;  // land and walls
    specs.push_back(a);
    Spec h = spec(o);
    h.lattice = Mla::Lattice::Hex;
    h.aperture = Mla::Aperture::Hex;
    specs.push_back(h);
    h.aperture = Mla::Aperture::Square;  // clipped by the hex cell: walls
    h.aperture_mm = 0.9;
    specs.push_back(h);
  }
  int refractions = 0, reflections = 0;
  int surfaces[4] = {0, 0, 0, 0};
  double worstSnell = 0.0, worstPlane = 0.0, worstRefl = 0.0;
  for (size_t si = 0; si < specs.size(); ++si) {
    auto mla = makeMla(specs[si]);
    for (int i = 0; i < 3000; ++i) {
      Rng rng = Rng::forSample(7, uint64_t(i), si);
      const double lambda = 400.0 + 300.0 * rng.uniformDouble();
      const double th = 1.3 * rng.uniformDouble(), ph = 2 * M_PI * rng.uniformDouble();
      Vec3d d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th));
      Point3d o(-3 + 6 * rng.uniformDouble(), -3 + 6 * rng.uniformDouble(), mla->frontZ() + 0.05);
      bool forward = i % 2 == 1;
      if (forward) {
        d.z = -d.z;
        o.z = mla->panelZ();
      }
      MlaTraceLog log;
      MlaExit ex;
      const bool ok = mla->trace(o, d, lambda, FresnelMode::Stochastic, &rng, ex, &log);
      if (ok) {
        EXPECT_TRUE(finite(ex.p) && finite(ex.d));
      }
      for (const MlaTraceEvent& e : log.events) {
        ++surfaces[int(e.surface)];
        EXPECT_NEAR(norm(e.dOut), 1.0, 1e-12);
        const double ci = dot(e.dIn, e.normal), co = dot(e.dOut, e.normal);
        if (e.action == MlaTraceEvent::Action::Refract) {
          ++refractions;
          const double a = e.nIn * norm(cross(e.dIn, e.normal)), b = e.nOut * norm(cross(e.dOut, e.normal));
          worstSnell = std::max(worstSnell, std::abs(a - b));
          worstPlane = std::max(worstPlane, std::abs(dot(e.dOut, cross(e.dIn, e.normal))));
          EXPECT_GT(ci * co, 0.0);  // transmitted: same side of the interface as it went
        } else {
          ++reflections;
          worstRefl = std::max(worstRefl, std::abs(ci + co));
          worstRefl = std::max(worstRefl, norm((e.dOut - co * e.normal) - (e.dIn - ci * e.normal)));
        }
      }
    }
  }
  std::printf("  %d refractions, %d reflections (cap %d, land %d, wall %d, flat %d); worst |n1 sin1 - n2 sin2| = "
              "%.1e, out-of-plane %.1e, reflection law %.1e\n",
              refractions, reflections, surfaces[0], surfaces[1], surfaces[2], surfaces[3], worstSnell, worstPlane,
              worstRefl);
  EXPECT_LT(worstSnell, 1e-12);
  EXPECT_LT(worstPlane, 1e-12);
  EXPECT_LT(worstRefl, 1e-12);
  EXPECT_GT(refractions, 20000);
  EXPECT_GT(reflections, 500);
  for (int s = 0; s < 4; ++s) EXPECT_GT(surfaces[s], 50) << "surface kind " << s;
}

// The first surface a ray meets, found by the cell walk, against brute force: marching along
// the ray in 0.2 um steps with the point-in-material test (which uses the nearest lens centre
// and the sag directly). The hit must be a real crossing of the boundary, and the march must
// see no crossing before it; rays the walk reports as missing the MLA must cross nothing.
TEST(RealMla, FirstHitMatchesBruteForceMarch) {
  std::vector<Spec> specs;
  for (auto o : {kViewer, kPanel}) {
    Spec a = spec(o);
    a.cols = a.rows = 5;
    specs.push_back(a);
    a.aperture = Mla::Aperture::Circle;
    specs.push_back(a);
    a.aperture = Mla::Aperture::Square;
    a.aperture_mm = 0.8;
    specs.push_back(a);
    Spec h = a;
    h.lattice = Mla::Lattice::Hex;
    h.aperture = Mla::Aperture::Hex;
    h.aperture_mm = 1.0;
    specs.push_back(h);
    h.aperture = Mla::Aperture::Square;
    h.aperture_mm = 0.9;
    specs.push_back(h);
  }
  int hits = 0, misses = 0, side = 0, segments = 0;
  for (size_t si = 0; si < specs.size(); ++si) {
    auto mla = makeMla(specs[si]);
    const double zTop = mla->frontZ(), zBot = mla->backZ();
    for (int i = 0; i < 150; ++i) {
      Rng rng = Rng::forSample(21, uint64_t(i), si);
      // From above (backward) or below (forward), steep to grazing.
      const bool fromAbove = i % 2 == 0;
      const double th = (i % 3 == 0 ? 1.45 : 1.2) * rng.uniformDouble(), ph = 2 * M_PI * rng.uniformDouble();
      Vec3d d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), fromAbove ? -std::cos(th) : std::cos(th));
      const Point3d target(-1.5 + 3 * rng.uniformDouble(), -1.5 + 3 * rng.uniformDouble(),
                           zBot + (zTop - zBot) * rng.uniformDouble());
      const double back = fromAbove ? (zTop + 0.01 - target.z) / -d.z : (target.z - (zBot - 0.01)) / d.z;
      const Point3d o = target - back * d;
      MlaTraceLog log;
      MlaExit ex;
      const bool ok = mla->trace(o, d, kLambdaDNm, FresnelMode::Off, nullptr, ex, &log);
      // March until the ray leaves the plate's z range (or 6 mm).
      const double step = 2e-4;
      double tEnd = 6.0;
      if (d.z != 0) tEnd = std::min(tEnd, std::max((zTop + 0.02 - o.z) / d.z, (zBot - 0.02 - o.z) / d.z));
      double tHit = log.events.empty() ? tEnd : dot(log.events[0].p - o, d);
      bool crossed = false;
      double tCross = 0.0;
      for (double t = step; t < tHit - 1e-6; t += step) {
        if (mla->insideMaterial(o + std::min(t, tHit - 1e-6) * d)) {
          crossed = true;
          tCross = t;
          break;
        }
      }
      if (!ok && log.events.empty()) {
        // Lost without a surface event: it met the plate's side (from outside the array's
        // footprint), so the march finds material.
        EXPECT_TRUE(crossed) << "spec " << si << " ray " << i;
        ++side;
        continue;
      }
      EXPECT_FALSE(crossed) << "spec " << si << " ray " << i << ": material at t = " << tCross << " before the hit at "
                            << tHit;
      if (!log.events.empty()) {
        ++hits;
        const Point3d p = log.events[0].p;
        EXPECT_FALSE(mla->insideMaterial(p - 1e-7 * d)) << "spec " << si << " ray " << i;
        EXPECT_TRUE(mla->insideMaterial(p + 1e-7 * d) || log.events[0].reflectance > 0.999)
            << "spec " << si << " ray " << i << " surface " << int(log.events[0].surface);
        // Every later segment (in glass or in air, between events) stays in one medium.
        bool inGlass = false;
        for (size_t k = 0; k < log.events.size(); ++k) {
          const MlaTraceEvent& e = log.events[k];
          if (e.action == MlaTraceEvent::Action::Refract) inGlass = !inGlass;
          const bool last = k + 1 == log.events.size();
          if (last && !ok) break;  // lost: left through the plate's side or the event limit
          const double len = last ? 1.0 : dot(log.events[k + 1].p - e.p, e.dOut);
          int wrong = 0;
          for (double t = 1e-6; t < len - 1e-6; t += step) wrong += mla->insideMaterial(e.p + t * e.dOut) != inGlass;
          EXPECT_EQ(wrong, 0) << "spec " << si << " ray " << i << " segment " << k << (inGlass ? " in glass" : " in air");
          ++segments;
        }
      } else {
        ++misses;
      }
    }
  }
  std::printf("  %d first hits, %d misses and %d side hits agree with the march; %d segments stay in their medium\n",
              hits, misses, side, segments);
  EXPECT_GT(hits, 1000);
}

// Fresnel: R + T = 1 with T from the transmission amplitudes (t_s, t_p) and the beam factor
// n2 cos(t) / (n1 cos(i)); normal incidence ((n - 1)/(n + 1))^2; Brewster's angle; TIR.
TEST(RealMla, FresnelEnergyConservation) {
  const double n = 1.4906;
  double worst = 0.0;
  for (auto [n1, n2] : std::vector<std::pair<double, double>>{{1.0, n}, {n, 1.0}}) {
    for (int i = 0; i <= 1000; ++i) {
      const double ci = i / 1000.0;
      const double R = fresnelReflectance(ci, n1, n2);
      EXPECT_GE(R, 0.0);
      EXPECT_LE(R, 1.0);
      const double s2 = (n1 / n2) * (n1 / n2) * (1 - ci * ci);
      if (s2 >= 1.0) {
        EXPECT_EQ(R, 1.0);  // TIR
        continue;
      }
      const double ct = std::sqrt(1 - s2);
      const double ts = 2 * n1 * ci / (n1 * ci + n2 * ct), tp = 2 * n1 * ci / (n2 * ci + n1 * ct);
      const double T = (n2 * ct) / (n1 * ci) * 0.5 * (ts * ts + tp * tp);
      if (ci > 0) worst = std::max(worst, std::abs(R + T - 1.0));
    }
    EXPECT_NEAR(fresnelReflectance(1.0, n1, n2), std::pow((n - 1) / (n + 1), 2), 1e-15);
    // Brewster: Rp = 0, so R = Rs / 2.
    const double thB = std::atan(n2 / n1), ciB = std::cos(thB);
    const double ctB = std::sqrt(1 - std::pow(n1 / n2 * std::sin(thB), 2));
    const double rs = (n1 * ciB - n2 * ctB) / (n1 * ciB + n2 * ctB);
    EXPECT_NEAR(fresnelReflectance(ciB, n1, n2), 0.5 * rs * rs, 1e-14);
  }
  std::printf("  worst |R + T - 1| = %.1e\n", worst);
  EXPECT_LT(worst, 1e-13);
  EXPECT_EQ(fresnelReflectance(0.0, 1.0, n), 1.0);  // grazing
}

// The Fresnel modes in a trace. A normal ray through the plate on a lenslet axis meets two
// interfaces at normal incidence: Weighted throughput (1 - R0)^2; Stochastic reflects at the
// first interface with frequency R0 (and transmits with 1 - R0: R + T = 1 in counts).
TEST(RealMla, FresnelModesInTrace) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const double n = mla->n(kLambdaDNm), R0 = std::pow((n - 1) / (n + 1), 2);
    MlaExit ex;
    ASSERT_TRUE(mla->trace({0, 0, mla->frontZ() + 1}, {0, 0, -1}, kLambdaDNm, FresnelMode::Weighted, nullptr, ex));
    EXPECT_NEAR(ex.throughput, (1 - R0) * (1 - R0), 1e-12);
    ASSERT_TRUE(mla->trace({0, 0, mla->frontZ() + 1}, {0, 0, -1}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
    EXPECT_EQ(ex.throughput, 1.0);
    const int N = 40000;
    int firstReflected = 0, reachedPanel = 0, backToViewer = 0;
    for (int i = 0; i < N; ++i) {
      Rng rng = Rng::forSample(3, uint64_t(i));
      MlaTraceLog log;
      MlaExit e;
      ASSERT_TRUE(mla->trace({0, 0, mla->frontZ() + 1}, {0, 0, -1}, kLambdaDNm, FresnelMode::Stochastic, &rng, e, &log));
      ASSERT_FALSE(log.events.empty());
      if (log.events[0].action == MlaTraceEvent::Action::Reflect) ++firstReflected;
      if (e.d.z < 0) ++reachedPanel;
      else ++backToViewer;
      EXPECT_EQ(e.throughput, 1.0);
    }
    const double sigma = std::sqrt(R0 * (1 - R0) / N);
    const double fr = double(firstReflected) / N;
    // Two interfaces and multiple reflections: P(panel) = (1-R)^2 / (1 - R^2) = (1-R)/(1+R).
    const double pPanel = (1 - R0) / (1 + R0);
    std::printf("  %s: R0 = %.5f, first-surface reflect frequency %.5f; to panel %.5f (expected %.5f)\n",
                orientationName(o), R0, fr, double(reachedPanel) / N, pPanel);
    EXPECT_NEAR(fr, R0, 4 * sigma);
    EXPECT_NEAR(double(reachedPanel) / N, pPanel, 4 * std::sqrt(pPanel * (1 - pPanel) / N));
    EXPECT_EQ(reachedPanel + backToViewer, N);  // energy: every ray either transmitted or reflected
  }
}

// Beer-Lambert: an axial ray crosses T of material: throughput exp(-alpha T).
TEST(RealMla, Absorption) {
  Spec s = spec(kViewer);
  s.options.absorptionPerMm = 0.2;
  s.options.fresnel = FresnelMode::Off;
  auto mla = makeMla(s);
  Rng rng(1, 1);
  PanelArrival pa;
  ASSERT_TRUE(mla->traceToPanel(Ray{Point3(0, 0, 2), Vec3(0, 0, -1)}, 550.0f, rng, pa));
  EXPECT_NEAR(pa.throughput, std::exp(-0.2 * 1.5), 1e-6);
  EXPECT_NEAR(pa.p.z, -3.3f, 1e-6);
}

namespace {

// A backward ray through (x, y) at the MLA's surface height there; Off mode (deterministic).
bool backward(const RealMla& mla, double x, double y, const Vec3d& d, PanelArrival& out, MlaExit* ex = nullptr) {
  // Start 2 mm above the front, on the line through (x, y, front).
  const Point3d start = Point3d(x, y, mla.frontZ()) - (2.0 / std::abs(d.z)) * d;
  MlaExit e;
  const bool ok = mla.trace(start, d, kLambdaDNm, FresnelMode::Off, nullptr, e);
  if (ex) *ex = e;
  if (!ok) return false;
  if (!(e.d.z < 0)) return false;
  const double t = (mla.panelZ() - e.p.z) / e.d.z;
  out.p = Point3(e.p + t * e.d);
  out.d = Vec3(e.d);
  out.lensletK = e.capK;
  out.lensletL = e.capL;
  return true;
}

}  // namespace

// Rays exactly on lenslet edges and corners (square: edges and 4-cell corners; hex: edges and
// 3-cell junctions): a valid result, no NaN, deterministic, and equal to the result of a ray
// moved 1e-12 mm to one side or the other (no crack between cells).
TEST(RealMla, RaysOnLensletEdgesAndCorners) {
  struct Case {
    Spec s;
    std::vector<std::pair<double, double>> points;
  };
  std::vector<Case> cases;
  for (auto o : {kViewer, kPanel}) {
    Case sq{spec(o), {{0.5, 0.2}, {0.5, 0.5}, {-0.5, -0.5}, {0.5, 0.0}, {1.5, -0.5}, {0.0, 0.5}}};
    cases.push_back(sq);
    Spec h = spec(o);
    h.lattice = Mla::Lattice::Hex;
    h.aperture = Mla::Aperture::Hex;
    const double v = 1.0 / std::sqrt(3.0);  // hex cell circumradius
    cases.push_back({h, {{0.0, v}, {0.5, 0.5 * v}, {0.5, 0.0}, {-0.5, -0.5 * v}, {0.25, 0.75 * v}}});
  }
  const std::vector<Vec3d> dirs = {{0, 0, -1}, unit({0.3, 0.2, -1}), unit({1, 1, -1}), unit({-0.2, 0.05, -1})};
  int n = 0, reached = 0;
  for (const Case& c : cases) {
    auto mla = makeMla(c.s);
    for (auto [x, y] : c.points)
      for (const Vec3d& d : dirs) {
        PanelArrival a, a2, l;
        MlaExit ea, ea2;
        const bool ok = backward(*mla, x, y, d, a, &ea);
        const bool ok2 = backward(*mla, x, y, d, a2, &ea2);
        EXPECT_TRUE(finite(ea.p) && finite(ea.d));
        EXPECT_EQ(ok, ok2);  // deterministic, bit for bit
        EXPECT_EQ(ea.p, ea2.p);
        EXPECT_EQ(ea.d, ea2.d);
        if (d.x == 0.0 && d.y == 0.0) {
          EXPECT_TRUE(ok) << x << "," << y;  // a normal ray always gets through
        }
        if (ok) {
          ++reached;
          EXPECT_TRUE(std::isfinite(a.p.x) && std::isfinite(a.p.y) && std::isfinite(a.d.x) && std::isfinite(a.d.z));
          EXPECT_GE(a.lensletK, 0);
        }
        // One-sided limits: the ray moved 1e-12 mm into each of the touching cells.
        const double e = 1e-12;
        bool matches = false;
        for (double sx : {-1.0, 1.0})
          for (double sy : {-1.0, 1.0}) {
            MlaExit el;
            backward(*mla, x + sx * e, y + sy * e, d, l, &el);
            if (norm(el.p - ea.p) < 1e-6 && norm(el.d - ea.d) < 1e-6) matches = true;
          }
        EXPECT_TRUE(matches) << latticeName(c.s.lattice) << " " << orientationName(c.s.orientation) << " at " << x
                             << "," << y << " dir " << d.x << "," << d.y;
        ++n;
      }
  }
  std::printf("  %d edge / corner rays, %d reach the panel (the others leave toward the viewer)\n", n, reached);
  EXPECT_EQ(n, 2 * (6 + 5) * 4);
}

// Grazing incidence on a spherical cap: rays tangent to a cap (discriminant ~ 0), shifted by
// -1e-9 .. 1e-9 mm along the normal. No NaN; a result or a clean miss; deterministic.
TEST(RealMla, GrazingIncidenceOnSphericalCap) {
  for (auto o : {kViewer, kPanel}) {
    for (auto mode : {FresnelMode::Off, FresnelMode::Weighted, FresnelMode::Stochastic}) {
      auto mla = makeMla(spec(o));
      const double s = o == kViewer ? 1.0 : -1.0;  // caps face +z (viewer) or -z
      int results = 0;
      for (auto [lx, ly] : std::vector<std::pair<double, double>>{{0.3, 0.1}, {0.0, 0.45}, {0.35, 0.35}, {0.05, 0.0}}) {
        const double r = std::hypot(lx, ly);
        const double zq = mla->vertexZ() - s * mla->capSag(r);
        // Outward normal of the sphere (centre on the axis at vertexZ - s R).
        const Vec3d nrm = unit(Vec3d(lx, ly, zq - (mla->vertexZ() - s * 1.62)));
        for (Vec3d e : {Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(-1, 0.3, 0), Vec3d(0.2, -1, 0)}) {
          Vec3d t = e - dot(e, nrm) * nrm;
          if (norm(t) < 1e-6) continue;
          t = unit(t);
          for (double eps : {-1e-9, -1e-13, 0.0, 1e-13, 1e-9}) {
            const Point3d q = Point3d(lx, ly, zq) + eps * nrm;
            // Travel along the tangent, from 3 mm before the touching point.
            const Vec3d d = o == kViewer ? (t.z <= 0 ? t : -t) : (t.z >= 0 ? t : -t);
            const Point3d start = q - 3.0 * d;
            MlaExit a, b;
            Rng r1(9, 1), r2(9, 1);
            const bool ok1 = mla->trace(start, d, kLambdaDNm, mode, &r1, a);
            const bool ok2 = mla->trace(start, d, kLambdaDNm, mode, &r2, b);
            EXPECT_EQ(ok1, ok2);
            if (ok1) {
              EXPECT_TRUE(finite(a.p) && finite(a.d));
              EXPECT_NEAR(norm(a.d), 1.0, 1e-12);
              EXPECT_EQ(a.p, b.p);
              EXPECT_TRUE(std::isfinite(a.throughput) && a.throughput >= 0 && a.throughput <= 1);
              ++results;
            }
          }
        }
      }
      EXPECT_GT(results, 0);
    }
  }
}

// TIR in the substrate: a ray inside the plate meets the flat face beyond the critical angle,
// reflects with equal angles, keeps bouncing and ends cleanly (leaves, or is lost at the bounce
// limit or the plate's side).
TEST(RealMla, TotalInternalReflectionInSubstrate) {
  for (auto o : {kViewer, kPanel}) {
    auto mla = makeMla(spec(o));
    const double zf = mla->flatZ();
    const double inward = o == kViewer ? 1.0 : -1.0;  // from the flat face into the plate
    const Point3d start(0.1, 0.05, zf + inward * 0.4);
    const double th = 60.0 * M_PI / 180.0;  // > critical angle asin(1/1.49) = 42.1 deg
    const Vec3d d(std::sin(th), 0.0, -inward * std::cos(th));
    ASSERT_TRUE(mla->insideMaterial(start));
    MlaTraceLog log;
    MlaExit ex;
    const bool ok = mla->trace(start, d, kLambdaDNm, FresnelMode::Off, nullptr, ex, &log);
    ASSERT_FALSE(log.events.empty());
    const MlaTraceEvent& e = log.events[0];
    EXPECT_EQ(e.surface, MlaTraceEvent::Surface::Flat);
    EXPECT_EQ(e.action, MlaTraceEvent::Action::Tir);
    EXPECT_NEAR(e.dOut.z, -e.dIn.z, 1e-15);
    EXPECT_NEAR(e.dOut.x, e.dIn.x, 1e-15);
    EXPECT_EQ(e.reflectance, 1.0);
    if (ok) {
      EXPECT_TRUE(finite(ex.p) && finite(ex.d));
      EXPECT_GE(ex.tir, 1);
    }
    std::printf("  %s: %zu events (%d TIR), %s\n", orientationName(o), log.events.size(),
                ok ? ex.tir : int(std::count_if(log.events.begin(), log.events.end(),
                                                [](auto& v) { return v.action == MlaTraceEvent::Action::Tir; })),
                ok ? "left the MLA" : "lost");
  }
  // A ray trapped by TIR between the flat face and the land (square apertures of 0.8 P, so
  // the land is flat) bounces until the bounce limit: a clean false, no loop.
  Spec s = spec(kViewer);
  s.aperture_mm = 0.5;
  s.options.maxEvents = 10;
  auto mla = makeMla(s);
  const double th = 80.0 * M_PI / 180.0;
  MlaTraceLog log;
  MlaExit ex;
  const Point3d start(0.5, 0.5, mla->flatZ() + 0.5);
  ASSERT_TRUE(mla->insideMaterial(start));
  EXPECT_FALSE(mla->trace(start, {std::sin(th), 0, -std::cos(th)}, kLambdaDNm, FresnelMode::Off, nullptr, ex, &log));
  EXPECT_LE(log.events.size(), 10u);
}

// Rays parallel to the panel: above the MLA, through the cap slab (between caps, along a cell
// edge where the caps are lowest), inside the substrate, below the MLA. Clean results, fast.
TEST(RealMla, RaysParallelToThePanel) {
  for (auto o : {kViewer, kPanel}) {
    Spec s = spec(o);
    s.cols = s.rows = 201;  // a long way to walk
    auto mla = makeMla(s);
    Rng rng(1, 2);
    PanelArrival pa;
    const auto t0 = std::chrono::steady_clock::now();
    for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0.6f, 0.8f, 0), Vec3(-0.70710678f, 0.70710678f, 0)}) {
      EXPECT_FALSE(mla->traceToPanel(Ray{Point3(0.1f, 0.2f, mla->frontZ() + 0.1f), d}, 550, rng, pa));
      EXPECT_FALSE(mla->traceToPanel(Ray{Point3(0.1f, 0.2f, mla->frontZ()), d}, 550, rng, pa));
    }
    const double s1 = o == kViewer ? 1.0 : -1.0;
    // In the cap slab, along the edge y = 0.5 at depth 0.05 mm (< the mid-edge sag 0.079):
    // air all the way, straight through the array.
    MlaExit ex;
    const Point3d inSlab(-50.0, 0.5, mla->vertexZ() - s1 * 0.05);
    ASSERT_FALSE(mla->insideMaterial(inSlab));
    ASSERT_TRUE(mla->trace(inSlab, {1, 0, 0}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
    EXPECT_EQ(ex.events, 0);
    EXPECT_EQ(ex.d, Vec3d(1, 0, 0));
    // Off the edge it meets a cap, refracts, and ends cleanly either way.
    for (double y : {0.3, 0.0, 0.45, 0.4999999}) {
      for (auto mode : {FresnelMode::Off, FresnelMode::Stochastic}) {
        const bool ok = mla->trace({-50.0, y, mla->vertexZ() - s1 * 0.05}, {1, 0, 0}, kLambdaDNm, mode, &rng, ex);
        if (ok) {
        EXPECT_TRUE(finite(ex.p) && finite(ex.d));
      }
      }
    }
    // Inside the substrate: reaches the plate's side, lost.
    const Point3d inPlate(0.0, 0.0, mla->flatZ() + s1 * 0.3);
    ASSERT_TRUE(mla->insideMaterial(inPlate));
    EXPECT_FALSE(mla->trace(inPlate, {1, 0, 0}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
    EXPECT_FALSE(mla->trace(inPlate, unit({1, 1, 0}), kLambdaDNm, FresnelMode::Off, nullptr, ex));
    // Below the MLA: misses it.
    ASSERT_TRUE(mla->trace({0, 0, mla->panelZ() + 0.5}, {1, 0, 0}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
    EXPECT_EQ(ex.events, 0);
    // Near-parallel (1e-12 rad) rays above the array reach the MLA far away or miss: clean.
    for (double dz : {-1e-12, -1e-6, -1e-3}) {
      const bool ok = mla->trace({0.1, 0.2, mla->frontZ() + 1e-3}, unit({1, 0, dz}), kLambdaDNm, FresnelMode::Off,
                                 nullptr, ex);
      if (ok) {
        EXPECT_TRUE(finite(ex.p) && finite(ex.d));
      }
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(ms, 2000.0);  // bounded walks (generous: shared machines)
  }
  // Degenerate inputs: zero or non-finite directions are a clean false.
  auto mla = makeMla(spec(kViewer));
  MlaExit ex;
  EXPECT_FALSE(mla->trace({0, 0, 1}, {0, 0, 0}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
  EXPECT_FALSE(mla->trace({0, 0, 1}, {NAN, 0, -1}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
  EXPECT_FALSE(mla->trace({INFINITY, 0, 1}, {0, 0, -1}, kLambdaDNm, FresnelMode::Off, nullptr, ex));
}

// Crosstalk: a steep ray that enters the plate over lenslet k leaves through lenslet k + 1's
// cap, and the lenslet reported is k + 1. Backward through a curved-toward-panel MLA, and
// forward from the panel through a curved-toward-viewer one.
TEST(RealMla, CrosstalkIntoNeighbourLenslet) {
  const double th = 48.0 * M_PI / 180.0;  // in glass: asin(sin 48 / 1.49) = 29.9 deg
  {
    Spec s = spec(kPanel);
    s.options.fresnel = FresnelMode::Off;
    auto mla = makeMla(s);
    const Vec3d d(std::sin(th), 0, -std::cos(th));
    const Point3d start = Point3d(0.0, 0.1, mla->frontZ()) - 1.0 * d;  // meets the flat face over lenslet 5
    MlaExit ex;
    ASSERT_TRUE(mla->trace(start, d, kLambdaDNm, FresnelMode::Off, nullptr, ex));
    EXPECT_EQ(ex.entryK, 5);
    EXPECT_EQ(ex.entryL, 5);
    EXPECT_EQ(ex.capK, 6);
    EXPECT_EQ(ex.capL, 5);
    Rng rng(1, 1);
    PanelArrival pa;
    ASSERT_TRUE(mla->traceToPanel(Ray{Point3(start), Vec3(d)}, float(kLambdaDNm), rng, pa));
    EXPECT_EQ(pa.lensletK, 6);
    EXPECT_EQ(pa.lensletL, 5);
    std::printf("  curved-toward-panel, backward: enters over lenslet %d, leaves through %d, lands at x = %.4f\n",
                ex.entryK, ex.capK, pa.p.x);
  }
  {
    auto mla = makeMla(spec(kViewer));
    const Vec3d d(std::sin(th), 0, std::cos(th));
    const Point3d start = Point3d(0.0, 0.1, mla->flatZ()) - ((mla->flatZ() - mla->panelZ()) / d.z) * d;
    MlaExit ex;
    ASSERT_TRUE(mla->traceToViewer(start, d, kLambdaDNm, nullptr, ex));
    EXPECT_EQ(ex.entryK, 5);
    EXPECT_EQ(ex.capK, 6);
    EXPECT_EQ(ex.capL, 5);
    std::printf("  curved-toward-viewer, forward: enters under lenslet %d, leaves through %d\n", ex.entryK, ex.capK);
  }
  // Backward through caps facing the viewer, a steep ray enters lenslet 5's cap near its
  // edge and leaves the flat face under lenslet 6: the lenslet reported is the cap it was
  // refracted by (5), the flat exit lies in cell 6.
  {
    auto mla = makeMla(spec(kViewer));
    const Vec3d d = unit({1.0, 0.0, -0.8});
    const Point3d start = Point3d(0.4, 0.0, mla->vertexZ() - mla->capSag(0.4)) - 2.0 * d;
    MlaTraceLog log;
    MlaExit ex;
    ASSERT_TRUE(mla->trace(start, d, kLambdaDNm, FresnelMode::Off, nullptr, ex, &log));
    ASSERT_EQ(log.events.size(), 2u);
    EXPECT_EQ(log.events[0].surface, MlaTraceEvent::Surface::Cap);
    EXPECT_EQ(log.events[0].k, 5);
    EXPECT_EQ(log.events[1].surface, MlaTraceEvent::Surface::Flat);
    EXPECT_EQ(log.events[1].k, 6);
    EXPECT_EQ(ex.capK, 5);
    std::printf("  curved-toward-viewer, backward: refracted by cap %d, leaves the flat face under cell %d\n",
                ex.capK, log.events[1].k);
  }
}

// Land and walls: outside a circular aperture the plate is flat (a normal ray goes straight
// through, no lenslet); a square aperture smaller than the pitch has walls.
TEST(RealMla, LandAndWalls) {
  for (auto o : {kViewer, kPanel}) {
    Spec c = spec(o);
    c.aperture = Mla::Aperture::Circle;
    c.options.fresnel = FresnelMode::Off;
    auto mla = makeMla(c);
    EXPECT_TRUE(mla->hasLand());
    EXPECT_NEAR(mla->apertureRadiusMm(), 0.5, 1e-15);
    Rng rng(1, 1);
    PanelArrival pa;
    ASSERT_TRUE(mla->traceToPanel(Ray{Point3(0.45f, 0.45f, 2.0f), Vec3(0, 0, -1)}, 550, rng, pa));
    EXPECT_EQ(pa.lensletK, -1);
    EXPECT_FLOAT_EQ(pa.p.x, 0.45f);
    EXPECT_EQ(pa.d, Vec3(0, 0, -1));
    ASSERT_TRUE(mla->traceToPanel(Ray{Point3(0.2f, 0.0f, 2.0f), Vec3(0, 0, -1)}, 550, rng, pa));
    EXPECT_EQ(pa.lensletK, 5);
    // On the aperture's rim exactly (cap meets land): valid.
    ASSERT_TRUE(mla->traceToPanel(Ray{Point3(0.5f, 0.0f, 2.0f), Vec3(0, 0, -1)}, 550, rng, pa));
    EXPECT_TRUE(std::isfinite(pa.p.x));

    Spec w = spec(o);
    w.aperture_mm = 0.8;
    auto mw = makeMla(w);
    EXPECT_TRUE(mw->hasLand());
    EXPECT_NEAR(mw->maxSagMm(), mw->capSag(0.4 * std::sqrt(2.0)), 1e-15);
    const double s = o == kViewer ? 1.0 : -1.0;
    // Inside the plate below the land... no: in the air notch beside a cap edge, moving toward it.
    const Point3d start(0.48, 0.0, mw->vertexZ() - s * 0.08);
    ASSERT_FALSE(mw->insideMaterial(start));
    MlaTraceLog log;
    MlaExit ex;
    mw->trace(start, unit({-1, 0, 0.0}), kLambdaDNm, FresnelMode::Off, nullptr, ex, &log);
    ASSERT_FALSE(log.events.empty());
    EXPECT_EQ(log.events[0].surface, MlaTraceEvent::Surface::Wall);
    EXPECT_NEAR(log.events[0].p.x, 0.4, 1e-12);
    EXPECT_NEAR(log.events[0].normal.x, 1.0, 1e-15);
  }
  // A cap that does not cover the aperture, caps deeper than the substrate, a panel inside the
  // MLA: errors that name the key.
  Spec bad = spec(kViewer);
  bad.radius = 0.6;
  EXPECT_THROW(makeMla(bad), InputError);
  bad = spec(kViewer);
  bad.thickness = 0.1;
  try {
    makeMla(bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "substrate_thickness_mm");
  }
  bad = spec(kViewer);
  bad.gap = 0.5;
  try {
    makeMla(bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "gap_mm");
  }
}

// Stochastic traces are deterministic for a given Rng stream, and thread-independent.
TEST(RealMla, DeterministicAcrossThreads) {
  auto mla = makeMla(spec(kViewer));
  auto run = [&](int i0, int i1, std::vector<PanelArrival>& out) {
    for (int i = i0; i < i1; ++i) {
      Rng rng = Rng::forSample(11, uint64_t(i));
      const float th = 0.6f * rng.uniform(), ph = 6.283f * rng.uniform();
      Ray r{Point3(-4 + 8 * rng.uniform(), -4 + 8 * rng.uniform(), 2.0f),
            Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th))};
      PanelArrival pa;
      if (!mla->traceToPanel(r, 550, rng, pa)) pa.lensletK = -2;
      out[size_t(i)] = pa;
    }
  };
  const int N = 20000;
  std::vector<PanelArrival> a(N), b(N);
  run(0, N, a);
  std::thread t1([&] { run(0, N / 2, b); }), t2([&] { run(N / 2, N, b); });
  t1.join();
  t2.join();
  for (int i = 0; i < N; ++i) {
    ASSERT_EQ(a[size_t(i)].p, b[size_t(i)].p);
    ASSERT_EQ(a[size_t(i)].lensletK, b[size_t(i)].lensletK);
  }
}

// traceToPanel speed (not a timed assertion: machines are shared): camera-like rays within
// 10 degrees of the axis over the whole array, Stochastic Fresnel, 1 and 2 threads.
TEST(RealMla, TraceToPanelSpeed) {
  Spec s = spec(kViewer);
  s.cols = 153;
  s.rows = 65;
  auto mla = makeMla(s);
  const int N = 1000000;
  std::vector<Ray> rays(N);
  Rng gen(5, 5);
  for (auto& r : rays) {
    const float th = 0.17f * std::sqrt(gen.uniform()), ph = 6.283f * gen.uniform();
    r = Ray{Point3(-75 + 150 * gen.uniform(), -32 + 64 * gen.uniform(), 2.0f),
            Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th))};
  }
  auto work = [&](int i0, int i1, int& hits) {
    PanelArrival pa;
    for (int i = i0; i < i1; ++i) {
      Rng rng = Rng::forSample(1, uint64_t(i));
      hits += mla->traceToPanel(rays[size_t(i)], 550.0f, rng, pa);
    }
  };
  int h1 = 0, h2a = 0, h2b = 0;
  auto cpuNow = [] {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
  };
  auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpuNow();
  work(0, N, h1);
  const double cpu1 = cpuNow() - c0;
  const double s1 = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  std::thread ta([&] { work(0, N / 2, h2a); }), tb([&] { work(N / 2, N, h2b); });
  ta.join();
  tb.join();
  const double s2 = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("  traceToPanel: %.2f M rays/s on 1 thread (%.2f M per CPU second of that thread), %.2f M rays/s on 2 "
              "threads (wall clock; %.1f %% reach the panel)\n",
              N / s1 / 1e6, N / cpu1 / 1e6, N / s2 / 1e6, 100.0 * h1 / N);
  EXPECT_EQ(h1, h2a + h2b);
  EXPECT_GT(h1, N / 2);
}

// The factory the view simulation calls: the paper display's MLA on the layout's lens centres.
TEST(RealMla, FactoryFromDisplay) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  std::unique_ptr<MlaModel> m = makeRealMla(d, L, d.reconstructionGapMm);
  ASSERT_TRUE(m);
  EXPECT_TRUE(m->isDispersive());
  auto real = RealMla::fromDisplay(d, L, d.reconstructionGapMm);
  const double n = real->n(kLambdaDNm);
  EXPECT_NEAR(m->frontZ(), 1.5 * (1 - 1 / n), 1e-6);  // curved toward the viewer, T = 1.5 mm
  EXPECT_GE(double(m->frontZ()), real->vertexZ());     // float, rounded up: rays from there start in air
  EXPECT_FALSE(real->insideMaterial(Point3d(L.lensX[76], L.lensY[32], double(m->frontZ()))));
  EXPECT_NEAR(real->panelZ(), -4.0, 1e-12);
  EXPECT_NEAR(real->focalLength(kLambdaDNm), 1.62 / (n - 1), 1e-12);
  for (int k : {0, 76, 152})
    for (int l : {0, 32, 64}) {
      EXPECT_NEAR(real->lensletCentre(k, l).x, L.lensX[size_t(k)], 1e-12);
      EXPECT_NEAR(real->lensletCentre(k, l).y, L.lensY[size_t(l)], 1e-12);
    }
  // A normal ray onto lenslet (10, 20)'s axis lands below it and reports it.
  Rng rng(1, 1);
  PanelArrival pa;
  const Ray r{Point3(float(L.lensX[10]), float(L.lensY[20]), 3.0f), Vec3(0, 0, -1)};
  int hits = 0;
  for (int i = 0; i < 10 && !hits; ++i) hits += m->traceToPanel(r, 550.0f, rng, pa);
  ASSERT_EQ(hits, 1);
  EXPECT_EQ(pa.lensletK, 10);
  EXPECT_EQ(pa.lensletL, 20);
  EXPECT_NEAR(pa.p.x, L.lensX[10], 1e-5);
  EXPECT_NEAR(pa.p.z, -4.0, 1e-6);
}
