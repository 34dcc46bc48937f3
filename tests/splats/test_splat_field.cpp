// The ray-traced splat field: against a brute-force evaluator that visits every Gaussian per
// ray, against closed forms for single Gaussians, and the SH colour against hand-computed
// values of the INRIA basis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "spectral/color.h"
#include "splats/splat_field.h"
#include "splats/splat_loaders.h"
#include "splats/splat_sh.h"

namespace inim {
namespace {

std::string dataFile(const std::string& rel) { return std::string(INIM_SOURCE_DATA_DIR) + "/" + rel; }

// ---- Brute force: every Gaussian, its max response from the covariance, sorted by t ---------

struct BruteResult {
  Vec3 rgb{0.0f};
  double opacity = 0.0, depth = INFINITY;
};

BruteResult bruteForce(const Gaussians& g, const Vec3& o, const Vec3& d, double tNear = 0.0, double tFar = INFINITY) {
  struct Sample {
    double t;
    size_t i;
    double alpha;
  };
  std::vector<Sample> samples;
  const glm::dvec3 od(o), dd(d);
  for (size_t i = 0; i < g.size(); ++i) {
    // Sigma^-1 = R S^-2 R^T; the response along the line peaks at
    // t* = d^T Sigma^-1 (mu - o) / d^T Sigma^-1 d.
    const glm::dmat3 R(quaternionToMatrix(g.rotation[i]));
    const glm::dvec3 s(g.scale[i]);
    const glm::dmat3 Sinv2(glm::dvec3(1.0 / (s.x * s.x), 0, 0), glm::dvec3(0, 1.0 / (s.y * s.y), 0),
                           glm::dvec3(0, 0, 1.0 / (s.z * s.z)));
    const glm::dmat3 P = R * Sinv2 * glm::transpose(R);
    const glm::dvec3 mu(g.position[i]);
    const double t = glm::dot(dd, P * (mu - od)) / glm::dot(dd, P * dd);
    const glm::dvec3 x = od + t * dd - mu;
    const double alpha = std::min(0.99, double(g.opacity[i]) * std::exp(-0.5 * glm::dot(x, P * x)));
    if (alpha < 1.0 / 255.0 || t < tNear || t > tFar) continue;
    samples.push_back({t, i, alpha});
  }
  std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.t < b.t || (a.t == b.t && a.i < b.i); });
  BruteResult r;
  double T = 1.0, depthSum = 0.0;
  const Vec3 du = glm::normalize(d);
  for (const Sample& s : samples) {
    const Vec3 c = splatShColour(g.shDegree, &g.sh[s.i * size_t(g.shPerSplat()) * 3], du);
    r.rgb += float(T * s.alpha) * c;
    depthSum += T * s.alpha * s.t;
    T *= 1.0 - s.alpha;
    if (T < 1e-3) break;
  }
  r.opacity = 1.0 - T;
  if (r.opacity > 0.0) r.depth = depthSum / r.opacity;
  return r;
}

Gaussians randomGaussians(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
  std::normal_distribution<float> normal;
  Gaussians g;
  g.resize(size_t(n), 3);
  for (size_t i = 0; i < size_t(n); ++i) {
    g.position[i] = Vec3(u(rng), u(rng), u(rng));
    g.scale[i] = glm::exp(Vec3(-3.5f + 2.0f * u01(rng), -3.5f + 2.0f * u01(rng), -3.5f + 2.0f * u01(rng)));
    g.rotation[i] = glm::normalize(glm::vec4(normal(rng), normal(rng), normal(rng), normal(rng)));
    g.opacity[i] = 0.02f + 0.97f * u01(rng);
    for (int k = 0; k < 16; ++k)
      for (int c = 0; c < 3; ++c) g.sh[(i * 16 + size_t(k)) * 3 + size_t(c)] = (k == 0 ? 1.0f : 0.3f) * u(rng);
  }
  return g;
}

struct TestRay {
  Vec3 o, d;
};
// Rays from a sphere of radius `r` around `centre` towards random points within `half` of it.
std::vector<TestRay> randomRays(int n, const Vec3& centre, float half, float r, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> normal;
  std::vector<TestRay> rays;
  for (int i = 0; i < n; ++i) {
    const Vec3 o = centre + r * glm::normalize(Vec3(normal(rng), normal(rng), normal(rng)));
    const Vec3 target = centre + half * Vec3(u(rng), u(rng), u(rng));
    rays.push_back({o, glm::normalize(target - o)});
  }
  return rays;
}

void expectMatchesBruteForce(const Gaussians& g, const std::vector<TestRay>& rays, int k, const char* what) {
  SplatTraceSettings settings;
  settings.kBuffer = k;
  const SplatField field(g, SplatFrame{}, settings);
  double evaluated = 0.0, traces = 0.0;
  int hitRays = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const SplatTraceResult r = field.trace(rays[i].o, rays[i].d, 0.0f, kInfinity);
    const BruteResult b = bruteForce(g, rays[i].o, rays[i].d);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(r.encodedRgb[c], b.rgb[c], 1e-3f) << what << " k " << k << " ray " << i;
    ASSERT_NEAR(r.opacity, b.opacity, 1e-4) << what << " ray " << i;
    if (b.opacity > 1e-2) {
      ASSERT_NEAR(r.depth, b.depth, 1e-3 * b.depth) << what << " ray " << i;
    }
    evaluated += r.evaluated;
    traces += r.traces;
    hitRays += b.opacity > 0.0;
  }
  std::printf("  %s, k = %d: %zu rays (%d hit), %.1f Gaussians composited and %.2f traversals per ray\n", what, k,
              rays.size(), hitRays, evaluated / double(rays.size()), traces / double(rays.size()));
  EXPECT_GT(hitRays, int(rays.size()) / 4) << "the rays must meet the splats for the comparison to mean anything";
}

// 300 random anisotropic Gaussians with SH 3: the k-buffer traversal gathers and orders the
// same samples as visiting every Gaussian, whatever k (k = 1 and 4 re-trace many times).
TEST(SplatField, MatchesBruteForceOnRandomGaussians) {
  const Gaussians g = randomGaussians(300, 7);
  const std::vector<TestRay> rays = randomRays(400, Vec3(0.0f), 0.9f, 4.0f, 11);
  for (int k : {1, 4, 16}) expectMatchesBruteForce(g, rays, k, "random Gaussians");
}

// The 100 splats are scattered: rays aim at splats (within a few of their sigmas) from all
// around, so most meet one or more.
TEST(SplatField, MatchesBruteForceOnTheHundredSplatFile) {
  const Gaussians g = loadGaussians(dataFile("tests/data/splats/cvlab_pc_short.ply"));
  Vec3 lo(kInfinity), hi(-kInfinity);
  for (const Vec3& p : g.position) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float radius = 2.0f * glm::length(hi - lo);
  std::mt19937 rng(5);
  std::normal_distribution<float> normal;
  std::vector<TestRay> rays;
  for (int i = 0; i < 400; ++i) {
    const size_t j = size_t(i) % g.size();
    const float sigma = std::max({g.scale[j].x, g.scale[j].y, g.scale[j].z});
    const Vec3 target = g.position[j] + sigma * Vec3(normal(rng), normal(rng), normal(rng));
    const Vec3 o = 0.5f * (lo + hi) + radius * glm::normalize(Vec3(normal(rng), normal(rng), normal(rng)));
    rays.push_back({o, glm::normalize(target - o)});
  }
  for (int k : {2, 16}) expectMatchesBruteForce(g, rays, k, "cvlab_pc_short.ply");
}

// ---- Closed forms --------------------------------------------------------------------------

Gaussians oneGaussian(const Vec3& mu, const Vec3& scale, const glm::vec4& q, float opacity, float colour) {
  Gaussians g;
  g.resize(1, 0);
  g.position[0] = mu;
  g.scale[0] = scale;
  g.rotation[0] = q;
  g.opacity[0] = opacity;
  for (int c = 0; c < 3; ++c) g.sh[size_t(c)] = (colour - 0.5f) / kShC0;
  return g;
}

// An isotropic Gaussian (sigma, opacity o) seen along any direction with impact distance b:
// alpha = o exp(-b^2 / (2 sigma^2)), the sample at the closest approach (t = 5 here), colour
// alpha * c; nothing once alpha < 1/255, i.e. beyond b = sigma sqrt(2 ln(255 o)).
TEST(SplatField, IsotropicGaussianHeadOnAndGrazing) {
  const Vec3 mu(0.3f, -0.2f, 0.5f);
  const float sigma = 0.1f, o = 0.8f, colour = 0.7f;
  const SplatField field(oneGaussian(mu, Vec3(sigma), glm::vec4(1, 0, 0, 0), o, colour));
  const float cutoff = sigma * std::sqrt(2.0f * std::log(255.0f * o));
  for (float angleDeg : {0.0f, 30.0f, 60.0f, 85.0f, 89.5f}) {
    const float a = glm::radians(angleDeg);
    const Vec3 d(std::sin(a), 0.0f, std::cos(a));
    const Vec3 n(0.0f, 1.0f, 0.0f);  // perpendicular to d
    for (float b : {0.0f, 0.05f, 0.15f, 0.999f * cutoff}) {
      const SplatTraceResult r = field.trace(mu - 5.0f * d + b * n, d, 0.0f, kInfinity);
      const float alpha = o * std::exp(-0.5f * b * b / (sigma * sigma));
      EXPECT_NEAR(r.opacity, alpha, 1e-5f) << angleDeg << " deg, b " << b;
      EXPECT_NEAR(r.encodedRgb.y, alpha * colour, 1e-5f);
      EXPECT_NEAR(r.depth, 5.0f, 1e-4f);
    }
    const SplatTraceResult miss = field.trace(mu - 5.0f * d + 1.001f * cutoff * n, d, 0.0f, kInfinity);
    EXPECT_EQ(miss.opacity, 0.0f) << angleDeg;
    EXPECT_EQ(miss.depth, kInfinity);
  }
  // alpha is capped at 0.99: an opaque Gaussian head-on leaves T = 0.01.
  const SplatField opaque(oneGaussian(mu, Vec3(sigma), glm::vec4(1, 0, 0, 0), 1.0f, colour));
  EXPECT_NEAR(opaque.trace(mu - Vec3(0, 0, 5), Vec3(0, 0, 1), 0.0f, kInfinity).opacity, 0.99f, 1e-6f);
  // The sample must lie in [tNear, tFar].
  EXPECT_EQ(field.trace(mu - Vec3(0, 0, 5), Vec3(0, 0, 1), 5.1f, kInfinity).opacity, 0.0f);
  EXPECT_EQ(field.trace(mu - Vec3(0, 0, 5), Vec3(0, 0, 1), 0.0f, 4.9f).opacity, 0.0f);
}

// A rotated anisotropic Gaussian: 90 deg about z takes its local x (sigma 0.3) to world y and
// its local y (sigma 0.02) to world -x. A ray along world y offset by (bx, 0, bz) sees
// d^2 = (bx / 0.02)^2 + (bz / 0.05)^2.
TEST(SplatField, RotatedAnisotropicGaussian) {
  const float h = std::sqrt(0.5f);
  const SplatField field(oneGaussian(Vec3(0.0f), Vec3(0.3f, 0.02f, 0.05f), glm::vec4(h, 0, 0, h), 0.9f, 1.0f));
  for (auto [bx, bz] : {std::pair{0.0f, 0.0f}, {0.01f, 0.0f}, {0.0f, 0.04f}, {0.02f, 0.05f}}) {
    const SplatTraceResult r = field.trace(Vec3(bx, -3.0f, bz), Vec3(0, 1, 0), 0.0f, kInfinity);
    const float d2 = (bx / 0.02f) * (bx / 0.02f) + (bz / 0.05f) * (bz / 0.05f);
    EXPECT_NEAR(r.opacity, 0.9f * std::exp(-0.5f * d2), 1e-5f) << bx << " " << bz;
    EXPECT_NEAR(r.depth, 3.0f, 1e-4f);
  }
  // Along the long axis offset sideways by 0.02 in z is well inside; along x, 0.02 is one sigma.
  EXPECT_NEAR(field.trace(Vec3(-3.0f, 0.1f, 0.0f), Vec3(1, 0, 0), 0.0f, kInfinity).opacity,
              0.9f * std::exp(-0.5f * (0.1f / 0.3f) * (0.1f / 0.3f)), 1e-5f);
}

// query() in the display frame: display = s R p + T moves rays into the splat frame; depth
// comes back in display units (s times the splat-frame t) and colour linearised with the sRGB
// EOTF (the trainer's colour is display-encoded).
TEST(SplatField, QueryInTheDisplayFrame) {
  const Vec3 mu(0.3f, -0.2f, 0.5f);
  SplatFrame frame;
  frame.scale = 10.0f;
  frame.rotation = glm::mat3(Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1));
  frame.translate = Vec3(1.0f, 2.0f, 3.0f);
  const SplatField field(oneGaussian(mu, Vec3(0.1f), glm::vec4(1, 0, 0, 0), 0.8f, 0.7f), frame);
  const Vec3 o = mu - Vec3(0.0f, 0.0f, 5.0f) + Vec3(0.05f, 0.0f, 0.0f), d(0, 0, 1);
  const SplatTraceResult r = field.trace(o, d, 0.0f, kInfinity);
  std::vector<FieldRay> rays(3);
  for (FieldRay& fr : rays) {
    fr.o = frame.toField(o);
    fr.d = frame.rotation * d;
  }
  rays[2].tNear = 60.0f;  // beyond the sample at 50 mm
  std::vector<FieldSample> out(3);
  field.query(rays, {}, out, 1);
  EXPECT_NEAR(out[0].depth, 50.0f, 1e-3f);
  EXPECT_NEAR(out[0].opacity, r.opacity, 1e-6f);
  EXPECT_NEAR(out[0].rgb.x, srgbDecode(0.7f * r.opacity), 1e-5f);
  EXPECT_EQ(out[1].rgb, out[0].rgb);
  EXPECT_EQ(out[2].opacity, 0.0f);
  EXPECT_EQ(field.colorSpace(), "lin_rec709");
  Point3 lo, hi;
  field.bounds(lo, hi);
  const Point3 c = frame.toField(mu);
  const float cut = 10.0f * 0.1f * std::sqrt(2.0f * std::log(255.0f * 0.8f));
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(lo[a], c[a] - cut, 1e-2f);
    EXPECT_NEAR(hi[a], c[a] + cut, 1e-2f);
  }
}

// A batch answers each ray as it would alone, whatever the split (deterministic, no state).
TEST(SplatField, BatchSplitDoesNotChangeAnswers) {
  const SplatField field(randomGaussians(200, 3));
  const std::vector<TestRay> tr = randomRays(300, Vec3(0.0f), 0.9f, 4.0f, 2);
  std::vector<FieldRay> rays(tr.size());
  for (size_t i = 0; i < tr.size(); ++i) rays[i].o = tr[i].o, rays[i].d = tr[i].d;
  std::vector<FieldSample> all(rays.size()), one(1);
  field.query(rays, {}, all, 1);
  for (size_t i = 0; i < rays.size(); i += 37) {
    field.query(std::span(rays).subspan(i, 1), {}, one, 99);
    EXPECT_EQ(one[0].rgb, all[i].rgb);
    EXPECT_EQ(one[0].depth, all[i].depth);
  }
}

// ---- SH colour against hand-computed values ------------------------------------------------

// The 16 INRIA basis functions at d = (2, -1, 2) / 3 (x = 2/3, y = -1/3, z = 2/3), worked by
// hand from the constants of utils/sh_utils.py.
double handBasis(int k) {
  const double C0 = 0.28209479177387814, C1 = 0.4886025119029199;
  const double C2[] = {1.0925484305920792, -1.0925484305920792, 0.31539156525252005, -1.0925484305920792, 0.5462742152960396};
  const double C3[] = {-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154,
                       -0.4570457994644658, 1.445305721320277, -0.5900435899266435};
  const double v[16] = {
      C0,
      -C1 * (-1.0 / 3),  // -C1 y
      C1 * (2.0 / 3),    // C1 z
      -C1 * (2.0 / 3),   // -C1 x
      C2[0] * (-2.0 / 9),             // xy
      C2[1] * (-2.0 / 9),             // yz
      C2[2] * (3.0 / 9),              // 2zz - xx - yy = (8 - 4 - 1) / 9
      C2[3] * (4.0 / 9),              // xz
      C2[4] * (3.0 / 9),              // xx - yy
      C3[0] * (-1.0 / 3) * (11.0 / 9),  // y (3xx - yy) = -1/3 (12 - 1) / 9
      C3[1] * (-4.0 / 27),              // xyz
      C3[2] * (-1.0 / 3) * (11.0 / 9),  // y (4zz - xx - yy) = -1/3 (16 - 5) / 9
      C3[3] * (2.0 / 3) * (-7.0 / 9),   // z (2zz - 3xx - 3yy) = 2/3 (8 - 12 - 3) / 9
      C3[4] * (2.0 / 3) * (11.0 / 9),   // x (4zz - xx - yy)
      C3[5] * (2.0 / 3) * (3.0 / 9),    // z (xx - yy)
      C3[6] * (2.0 / 3) * (1.0 / 9),    // x (xx - 3yy) = 2/3 (4 - 3) / 9
  };
  return v[k];
}

TEST(SplatSh, DegreesZeroToThreeMatchHandValues) {
  const Vec3 d = Vec3(2.0f, -1.0f, 2.0f) / 3.0f;
  for (int degree = 0; degree <= 3; ++degree) {
    const int n = splatShCount(degree);
    for (int k = 0; k < n; ++k) {
      std::vector<float> coeffs(size_t(n) * 3, 0.0f);
      coeffs[size_t(k) * 3 + 0] = 1.0f;   // red: +basis_k
      coeffs[size_t(k) * 3 + 1] = -1.0f;  // green: -basis_k
      const Vec3 c = splatShColour(degree, coeffs.data(), d);
      EXPECT_NEAR(c.x, 0.5 + handBasis(k), 1e-6) << "degree " << degree << " k " << k;
      EXPECT_NEAR(c.y, 0.5 - handBasis(k), 1e-6);
      EXPECT_EQ(c.z, 0.5f);
    }
  }
  // Clamped at 0, not below.
  const float dark[3] = {-5.0f, 0.0f, 0.0f};
  EXPECT_EQ(splatShColour(0, dark, d).x, 0.0f);
}

// Through the field: a degree-3 Gaussian seen along d shows alpha (0.5 + sum_k basis_k(d) c_k).
TEST(SplatSh, FieldColourIsTheShAlongTheRay) {
  Gaussians g = oneGaussian(Vec3(0.0f), Vec3(0.2f), glm::vec4(1, 0, 0, 0), 0.6f, 0.5f);
  Gaussians g3;
  g3.resize(1, 3);
  g3.position = g.position, g3.scale = g.scale, g3.rotation = g.rotation, g3.opacity = g.opacity;
  double expected = 0.5;
  for (int k = 0; k < 16; ++k) {
    const float c = 0.05f * float(k % 5) - 0.1f;
    g3.sh[size_t(k) * 3] = c;
    expected += c * handBasis(k);
  }
  const SplatField field(std::move(g3));
  const Vec3 d = Vec3(2.0f, -1.0f, 2.0f) / 3.0f;
  const SplatTraceResult r = field.trace(-4.0f * d, d, 0.0f, kInfinity);
  EXPECT_NEAR(r.opacity, 0.6f, 1e-6f);
  EXPECT_NEAR(r.encodedRgb.x, 0.6 * expected, 1e-5);
  EXPECT_NEAR(r.encodedRgb.y, 0.6 * 0.5, 1e-6);
}

}  // namespace
}  // namespace inim
