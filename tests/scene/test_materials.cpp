// Fresnel, Snell, conductor reflectance and thin-sheet sums against analytic references.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "scene/materials.h"
#include "spectral/dispersion.h"

using namespace inim;

namespace {
// Fresnel transmittance from the amplitude coefficients, independent of fresnelDielectric.
double fresnelT(double cosI, double n1, double n2) {
  double sinI = std::sqrt(std::max(0.0, 1 - cosI * cosI));
  double sinT = n1 / n2 * sinI;
  if (sinT >= 1) return 0;
  double cosT = std::sqrt(1 - sinT * sinT);
  double ts = 2 * n1 * cosI / (n1 * cosI + n2 * cosT);
  double tp = 2 * n1 * cosI / (n2 * cosI + n1 * cosT);
  return (n2 * cosT) / (n1 * cosI) * 0.5 * (ts * ts + tp * tp);
}
}  // namespace

// Energy: R + T = 1 at every angle, from both sides (T from the amplitude coefficients).
TEST(Fresnel, ReflectancePlusTransmittanceIsOne) {
  for (double n : {1.0, 1.33, 1.5168, 1.9, 2.4}) {
    for (int i = 0; i <= 90; ++i) {
      double cosI = std::cos(i * M_PI / 180.0 * 0.999);
      double R = fresnelDielectric(float(cosI), float(n));
      EXPECT_NEAR(R + fresnelT(cosI, 1.0, n), 1.0, 1e-5) << "n " << n << " angle " << i;
      double Rin = fresnelDielectric(float(-cosI), float(n));  // from inside the glass
      double Tin = fresnelT(cosI, n, 1.0);
      if (Tin > 0) {
        EXPECT_NEAR(Rin + Tin, 1.0, 1e-5) << "inside, n " << n << " angle " << i;
      } else {
        EXPECT_EQ(Rin, 1.0) << "beyond the critical angle: TIR";
      }
    }
  }
}

TEST(Fresnel, NormalIncidence) {
  for (float n : {1.33f, 1.5f, 1.5168f, 2.4f}) {
    float expected = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    EXPECT_NEAR(fresnelDielectric(1.0f, n), expected, 1e-7f);
    EXPECT_NEAR(fresnelDielectric(-1.0f, n), expected, 1e-7f);  // same from inside
  }
  // Brewster angle: R_p = 0, so R = R_s / 2.
  float n = 1.5f, thetaB = std::atan(n);
  float cosI = std::cos(thetaB), cosT = std::cos(std::asin(std::sin(thetaB) / n));
  float rs = (cosI - n * cosT) / (cosI + n * cosT);
  EXPECT_NEAR(fresnelDielectric(cosI, n), 0.5f * rs * rs, 1e-6f);
}

// Snell: n1 sin(theta1) = n2 sin(theta2) for refracted directions, both ways.
TEST(Fresnel, RefractionObeysSnell) {
  Rng rng(3, 4);
  Vec3 nrm(0, 0, 1);
  for (int k = 0; k < 2000; ++k) {
    float cz = rng.uniform();
    float phi = 2 * kPi * rng.uniform();
    float s = std::sqrt(1 - cz * cz);
    bool inside = k % 2;
    Vec3 wi(s * std::cos(phi), s * std::sin(phi), inside ? -cz : cz);
    float n = 1.5168f;
    float etap;
    Vec3 wt;
    bool ok = refract(wi, nrm, n, &etap, &wt);
    float sinI = s;
    float n1 = inside ? n : 1.0f, n2 = inside ? 1.0f : n;
    if (n1 * sinI / n2 >= 1.0f) {
      EXPECT_FALSE(ok);
      EXPECT_EQ(fresnelDielectric(inside ? -cz : cz, n), 1.0f);
      continue;
    }
    ASSERT_TRUE(ok);
    EXPECT_NEAR(glm::length(wt), 1.0f, 1e-5f);
    float sinT = std::sqrt(wt.x * wt.x + wt.y * wt.y);
    EXPECT_NEAR(n1 * sinI, n2 * sinT, 2e-5f);
    EXPECT_LT(wt.z * wi.z, 0.0f);  // crosses the interface
    // Stays in the plane of incidence.
    EXPECT_NEAR(wt.x * wi.y - wt.y * wi.x, 0.0f, 1e-5f);
  }
}

// Conductor at normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2); Cu at 600 nm.
TEST(Fresnel, ConductorNormalIncidenceCopper) {
  const ConductorIndex& cu = MaterialCatalog::standard().conductor("Cu");
  float n = (*cu.eta)(600.0f), k = (*cu.k)(600.0f);
  float expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
  EXPECT_NEAR(fresnelConductor(1.0f, n, k), expected, 1e-6f);
  // Copper is red: it reflects 650 nm much better than 450 nm.
  auto R = [&](float l) { return fresnelConductor(1.0f, (*cu.eta)(l), (*cu.k)(l)); };
  EXPECT_GT(R(650.0f), R(450.0f) + 0.2f);
  EXPECT_GT(expected, 0.5f);
  // k = 0 reduces to the dielectric formula.
  EXPECT_NEAR(fresnelConductor(0.7f, 1.5f, 0.0f), fresnelDielectric(0.7f, 1.5f), 1e-6f);
  // Grazing incidence reflects everything.
  EXPECT_NEAR(fresnelConductor(0.0f, n, k), 1.0f, 1e-6f);
}

TEST(Fresnel, ThinSheetSumsAllReflections) {
  // Explicit series: T = (1-R)^2 tau sum (R tau)^(2m), R_tot = R + (1-R)^2 tau^2 R sum (...).
  for (float R : {0.0f, 0.04f, 0.2f}) {
    for (float tau : {1.0f, 0.7f, 0.1f}) {
      double T = 0, Rt = R, a = (1 - R) * (1 - R) * tau;
      for (int m = 0; m < 200; ++m) {
        T += a * std::pow(double(R) * tau, 2 * m);
        Rt += a * tau * R * std::pow(double(R) * tau, 2 * m);
      }
      float rt, tt;
      thinSheet(R, tau, &rt, &tt);
      EXPECT_NEAR(tt, T, 1e-6);
      EXPECT_NEAR(rt, Rt, 1e-6);
      if (tau == 1.0f) {
        EXPECT_NEAR(rt + tt, 1.0f, 1e-6f);  // a lossless sheet conserves energy
      }
    }
  }
}

TEST(Microfacet, GgxNormalisedAndPdfMatchesSampling) {
  // Projected-area normalisation: integral of D(wm) cos(theta_m) d(omega) = 1 (1D in theta).
  for (float alpha : {0.02f, 0.1f, 0.3f, 0.8f}) {
    double sum = 0;
    int n = 200000;
    for (int i = 0; i < n; ++i) {
      double th = (i + 0.5) / n * M_PI / 2;
      Vec3 wm(float(std::sin(th)), 0.0f, float(std::cos(th)));
      sum += ggx::D(wm, alpha) * std::cos(th) * std::sin(th) * (M_PI / 2 / n) * 2 * M_PI;
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << alpha;
  }
  // Importance sampling: E[f cos / pdf] equals the albedo estimated by uniform sampling.
  Material m;
  m.type = MaterialType::Conductor;
  m.eta = BakedSpectrum(0.2f);
  m.k = BakedSpectrum(3.0f);
  m.alpha = 0.3f;
  SampledWavelengths l = SampledWavelengths::sampleUniform(0.5f);
  Vec3 wo = glm::normalize(Vec3(0.3f, 0.1f, 0.9f));
  Rng rng(9, 9);
  double is = 0, uni = 0;
  int n = 200000;
  for (int i = 0; i < n; ++i) {
    Vec2 u(rng.uniform(), rng.uniform());
    Vec3 wm = ggx::sampleWm(wo, u, m.alpha);
    Vec3 wi = reflect(wo, wm);
    float pdf = ggx::pdfReflect(wo, wi, m.alpha);
    if (wi.z > 0 && pdf > 0) is += roughConductorF(m, wo, wi, l)[0] * wi.z / pdf;
    float z = rng.uniform(), phi = 2 * kPi * rng.uniform(), s = std::sqrt(1 - z * z);
    Vec3 w(s * std::cos(phi), s * std::sin(phi), z);
    uni += roughConductorF(m, wo, w, l)[0] * z * 2 * M_PI;
  }
  EXPECT_NEAR(is / n, uni / n, 0.02 * uni / n);
}
