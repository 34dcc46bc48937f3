#include <gtest/gtest.h>

#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"

using namespace inim;

TEST(Rng, StreamsDependOnlyOnSeedIndexSample) {
  Rng a = Rng::forSample(7, 12345, 3), b = Rng::forSample(7, 12345, 3);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.nextU32(), b.nextU32());
  Rng c = Rng::forSample(7, 12346, 3);
  Rng d = Rng::forSample(7, 12345, 3);
  int same = 0;
  for (int i = 0; i < 100; ++i) same += c.nextU32() == d.nextU32();
  EXPECT_LT(same, 3);
}

TEST(Rng, UniformMeanAndRange) {
  Rng r(1, 2);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    float u = r.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  EXPECT_NEAR(sum / n, 0.5, 3e-3);  // 5 sigma of 1/sqrt(12 n)
}

// The same per-index work on 1 thread and on 2 threads gives bit-identical output.
TEST(Parallel, BitIdenticalForAnyThreadCount) {
  auto run = [](int threads) {
    ThreadLimit limit(threads);
    std::vector<float> out(300 * 200);
    parallelForTiles(300, 200, [&](const Tile& t) {
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) {
          Rng rng = Rng::forSample(42, uint64_t(y) * 300 + x);
          float acc = 0;
          for (int s = 0; s < 16; ++s) acc += sampleCosineHemisphere({rng.uniform(), rng.uniform()}).z;
          out[size_t(y) * 300 + x] = acc;
        }
    });
    return out;
  };
  EXPECT_EQ(run(1), run(2));
}

TEST(Sampling, CosineHemisphereIsUnitAndUpper) {
  Rng r(3, 4);
  for (int i = 0; i < 1000; ++i) {
    Vec3 w = sampleCosineHemisphere({r.uniform(), r.uniform()});
    EXPECT_NEAR(glm::length(w), 1.0f, 1e-5f);
    EXPECT_GE(w.z, 0.0f);
  }
}
