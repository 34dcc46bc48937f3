// The march and its analytic gradients: central finite differences on a tiny grid, and the
// edge cases (empty space, a ray missing the box, an empty interval, black background).
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "radiance/trainer.h"
#include "radiance/volume_renderer.h"

using namespace inim;

namespace {

VoxelGrid randomGrid(int degree, uint64_t seed) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(5, 4, 6), degree,
                                  DensityActivation::Softplus, Vec3(1.0f), 0.1f);
  Rng rng(seed, 1);
  for (float& d : g.density) d = -2.0f + 4.0f * rng.uniform();
  for (float& c : g.color) c = -1.0f + 2.0f * rng.uniform();
  return g;
}

TrainingRays randomRays(int n, uint64_t seed) {
  TrainingRays rays;
  Rng rng(seed, 2);
  for (int i = 0; i < n; ++i) {
    Vec3 o(3.0f * (rng.uniform() - 0.5f), 3.0f * (rng.uniform() - 0.5f), 3.0f);
    Vec3 target(0.8f * (rng.uniform() - 0.5f), 0.8f * (rng.uniform() - 0.5f), 0.0f);
    rays.origin.push_back(o);
    rays.dir.push_back(target - o);
    rays.rgb.push_back(Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
  }
  return rays;
}

void checkGradients(int degree) {
  VoxelGrid g = randomGrid(degree, 7 + degree);
  TrainingRays rays = randomRays(8, 3);
  MarchSettings march;
  march.minTransmittance = 0.0f;  // no termination: the loss is smooth in every parameter
  std::vector<float> gd, gc, unused1, unused2;
  lossAndGradient(g, rays, march, gd, gc);
  float maxGrad = 0.0f;
  for (float v : gd) maxGrad = std::max(maxGrad, std::abs(v));
  for (float v : gc) maxGrad = std::max(maxGrad, std::abs(v));
  ASSERT_GT(maxGrad, 1e-4f);
  const float eps = 1e-2f;
  auto numeric = [&](float& p) {
    float keep = p;
    p = keep + eps;
    double lp = lossAndGradient(g, rays, march, unused1, unused2);
    p = keep - eps;
    double lm = lossAndGradient(g, rays, march, unused1, unused2);
    p = keep;
    return float((lp - lm) / (2.0 * eps));
  };
  int checked = 0;
  for (size_t i = 0; i < g.density.size(); ++i) {
    float n = numeric(g.density[i]);
    EXPECT_NEAR(gd[i], n, 2e-3f * maxGrad + 2e-2f * std::abs(n)) << "density " << i;
    ++checked;
  }
  for (size_t i = 0; i < g.color.size(); ++i) {
    float n = numeric(g.color[i]);
    EXPECT_NEAR(gc[i], n, 2e-3f * maxGrad + 2e-2f * std::abs(n)) << "colour " << i;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

}  // namespace

TEST(RayMarch, GradientsMatchFiniteDifferencesDegree0) { checkGradients(0); }
TEST(RayMarch, GradientsMatchFiniteDifferencesDegree1) { checkGradients(1); }
TEST(RayMarch, GradientsMatchFiniteDifferencesDegree2) { checkGradients(2); }

TEST(RayMarch, EmptySpaceReturnsBackground) {
  for (Vec3 bg : {Vec3(1.0f), Vec3(0.0f)}) {
    VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(16), 1,
                                    DensityActivation::Softplus, bg, 0.01f);
    std::fill(g.density.begin(), g.density.end(), -30.0f);  // empty everywhere
    VolumeRenderer r(g);
    RadianceSample res = r.render(RenderRay{Point3(0, 0, 3), Vec3(0, 0, -1)});
    EXPECT_EQ(res.rgb, bg);
    EXPECT_EQ(res.opacity, 0.0f);
    EXPECT_EQ(res.depth, kInfinity);
  }
}

TEST(RayMarch, MissEmptyIntervalAndDegenerateRays) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(16), 1,
                                  DensityActivation::Softplus, Vec3(0.0f), 0.5f);
  VolumeRenderer r(g);
  // The grid is fog (opacity 0.5 per cell): a ray through it is nearly opaque.
  RadianceSample through = r.render(RenderRay{Point3(0, 0, 3), Vec3(0, 0, -1)});
  EXPECT_GT(through.opacity, 0.99f);
  EXPECT_NEAR(through.rgb.x, 0.5f, 1e-3f);  // SH 0 -> sigmoid(0)
  EXPECT_GT(through.depth, 2.0f);
  EXPECT_LT(through.depth, 3.0f);
  RadianceSample miss = r.render(RenderRay{Point3(0, 3, 3), Vec3(0, 0, -1)});
  EXPECT_EQ(miss.opacity, 0.0f);
  EXPECT_EQ(miss.depth, kInfinity);
  RadianceSample empty = r.render(RenderRay{Point3(0, 0, 3), Vec3(0, 0, -1), 2.5f, 1.0f});
  EXPECT_EQ(empty.opacity, 0.0f);
  RadianceSample beforeBox = r.render(RenderRay{Point3(0, 0, 3), Vec3(0, 0, -1), 0.0f, 1.5f});
  EXPECT_EQ(beforeBox.opacity, 0.0f);
  RadianceSample zeroDir = r.render(RenderRay{Point3(0, 0, 3), Vec3(0.0f)});
  EXPECT_EQ(zeroDir.opacity, 0.0f);
  RadianceSample nanRay = r.render(RenderRay{Point3(NAN, 0, 3), Vec3(0, 0, -1)});
  EXPECT_EQ(nanRay.opacity, 0.0f);
  // A ray parallel to an axis along the box face is still well defined.
  RadianceSample face = r.render(RenderRay{Point3(-1.0f, -1.0f, 3), Vec3(0, 0, -1)});
  EXPECT_TRUE(std::isfinite(face.rgb.x));
}

// Beer-Lambert through uniform fog: opacity a per cell, a ray down the 15-cell box has
// transmittance (1 - a)^15 whatever the step. Steps of 1, 1/2 and 0.3 cells take the march's
// three ways to a sample's opacity (softplus), and ReLU its fourth; thin fog checks small
// opacities.
TEST(RayMarch, UniformFogFollowsBeerLambertAtEveryStep) {
  for (DensityActivation act : {DensityActivation::Softplus, DensityActivation::ReLU})
    for (float a : {0.1f, 1e-4f})
      for (float step : {1.0f, 0.5f, 0.3f}) {
        VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(16), 0, act, Vec3(0.0f), a);
        VolumeRenderer r(g, MarchSettings{step, 0.0f, 0.0f});
        const RadianceSample res = r.render(RenderRay{Point3(0, 0, 3), Vec3(0, 0, -1)});
        const double expected = 1.0 - std::pow(1.0 - double(a), 15.0);
        // Thin fog: T *= 1 - alpha rounds by up to 6e-8 per sample, 2e-3 of alpha = 3e-5.
        const double tol = (a > 0.01f ? 1e-5 : 1e-3) * expected;
        EXPECT_NEAR(res.opacity, expected, tol) << "a " << a << ", step " << step << ", relu " << int(act);
        EXPECT_NEAR(res.rgb.x, 0.5 * expected, tol);  // SH 0 -> sigmoid(0) = 1/2
      }
}

// A ray ended early (fog of opacity 1/2 per cell, ended at 10 % transmittance over a black
// background): by default the rest is background, so the colour is darker than the fog's;
// completed, the rest is what the ray has seen: the fog's colour, opacity 1, the same depth.
TEST(RayMarch, EndedRayCompletedWithWhatItHasSeen) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(16), 0, DensityActivation::Softplus,
                                  Vec3(0.0f), 0.5f);
  const RenderRay ray{Point3(0, 0, 3), Vec3(0, 0, -1)};
  const RadianceSample plain = VolumeRenderer(g, MarchSettings{1.0f, 0.1f, 1e-3f, false}).render(ray);
  const RadianceSample done = VolumeRenderer(g, MarchSettings{1.0f, 0.1f, 1e-3f, true}).render(ray);
  EXPECT_NEAR(plain.opacity, 1.0 - 0.0625, 1e-6);  // ended after 4 cells: T = 1/16
  EXPECT_NEAR(plain.rgb.x, 0.5 * (1.0 - 0.0625), 1e-6);
  EXPECT_EQ(done.opacity, 1.0f);
  EXPECT_NEAR(done.rgb.x, 0.5, 1e-6);  // SH 0 -> sigmoid(0)
  EXPECT_NEAR(done.depth, plain.depth, 1e-6);
}

// Haze of opacity a per cell in front (z > 0, grey 1/2), an opaque back (z < 0, red-white
// sigmoid(4)), on a black background; SH 0, so colour = sigmoid(Y00 * coefficient).
VoxelGrid hazeOverWall(float haze) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(16), 0, DensityActivation::Softplus,
                                  Vec3(0.0f), haze);
  const float wall = g.actInverse(-std::log(1.0f - 0.9f));
  for (int x = 0; x < 16; ++x)
    for (int y = 0; y < 16; ++y)
      for (int z = 0; z < 8; ++z) {
        const size_t i = g.index(x, y, z);
        g.density[i] = wall;
        for (int c = 0; c < 3; ++c) g.color[3 * i + size_t(c)] = 4.0f / 0.28209479f;
      }
  return g;
}

// Leaving out the colour of the faint samples changes neither opacity nor depth, and moves the
// colour by at most the budget times the spread of the colours (here sigmoid(4) - 1/2);
// with no budget it leaves nothing out.
TEST(RayMarch, ColourLeftOutOnlyWithinItsBudget) {
  const VoxelGrid g = hazeOverWall(0.004f);
  const RenderRay ray{Point3(0, 0, 3), Vec3(0, 0, -1)};
  const MarchSettings exact{1.0f, 0.0f, 0.0f};
  const RadianceSample ref = VolumeRenderer(g, exact).render(ray);
  const double spread = 1.0 / (1.0 + std::exp(-4.0)) - 0.5;
  for (float budget : {0.0f, 0.001f, 0.01f, 0.05f}) {
    MarchSettings cheap = exact;
    cheap.colourMinWeight = 0.01f;  // every haze sample (0.004 of the light) is under it
    cheap.colourSkipBudget = budget;
    const RadianceSample res = VolumeRenderer(g, cheap).render(ray);
    EXPECT_EQ(res.opacity, ref.opacity);
    EXPECT_EQ(res.depth, ref.depth);
    for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs(res.rgb[c] - ref.rgb[c]), budget * spread + 1e-6) << budget;
    if (budget == 0.0f) {
      EXPECT_EQ(res.rgb, ref.rgb);
    } else if (budget >= 0.01f) {
      EXPECT_GT(std::abs(res.rgb.x - ref.rgb.x), 1e-4) << "nothing was left out";
    }
  }
}

// A ray whose every sample is left out (thin haze, 1.5 % of the light in all, under a 5 %
// budget) takes the background for it: off by that light times |haze colour - background|.
TEST(RayMarch, AllColourLeftOutTakesTheBackground) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(16), 0, DensityActivation::Softplus,
                                  Vec3(1.0f), 0.001f);
  const RenderRay ray{Point3(0, 0, 3), Vec3(0, 0, -1)};
  MarchSettings cheap{1.0f, 0.0f, 0.0f};
  cheap.colourMinWeight = 0.01f;
  cheap.colourSkipBudget = 0.05f;
  const RadianceSample ref = VolumeRenderer(g, MarchSettings{1.0f, 0.0f, 0.0f}).render(ray);
  const RadianceSample res = VolumeRenderer(g, cheap).render(ray);
  EXPECT_NEAR(ref.opacity, 1.0 - std::pow(0.999, 15.0), 1e-6);
  EXPECT_NEAR(res.rgb.x, 1.0f, 1e-6);  // all background
  EXPECT_NEAR(res.rgb.x - ref.rgb.x, 0.5 * ref.opacity, 1e-6);
}

TEST(RayMarch, PsnrHelper) {
  std::vector<Vec3> a{Vec3(0.5f), Vec3(0.5f)}, b{Vec3(0.6f), Vec3(0.4f)};
  EXPECT_NEAR(psnr(a, b), 20.0, 1e-4);
}
