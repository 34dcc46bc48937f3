// PathRandom (scene/path_random.h): the first light sample of the samples of one id is
// stratified (each of n = 2^k samples in its own 1/n of every dimension), shared by rays of one
// stratum, different between ids, and later light samples are independent draws.
#include <gtest/gtest.h>

#include <set>

#include "scene/path_random.h"

using namespace inim;

TEST(PathRandom, FirstLightSamplesOfAnIdAreStratified) {
  for (uint32_t n : {4u, 8u, 32u}) {
    std::set<int> select, ux, uy;
    for (uint32_t i = 0; i < n; ++i) {
      PathRandom r(5, 1234, i, i);
      const LightUniforms q = r.light();
      select.insert(int(q.select * float(n)));
      ux.insert(int(q.u.x * float(n)));
      uy.insert(int(q.u.y * float(n)));
    }
    EXPECT_EQ(select.size(), n);
    EXPECT_EQ(ux.size(), n);
    EXPECT_EQ(uy.size(), n);
  }
}

TEST(PathRandom, RaysOfOneStratumShareTheirLightSampleAndIdsDiffer) {
  // A dispersive camera's 4 rays of one sample: samples 8..11, stratum 2.
  PathRandom a(5, 77, 8, 2), b(5, 77, 11, 2), other(5, 78, 8, 2);
  const LightUniforms qa = a.light(), qb = b.light(), qo = other.light();
  EXPECT_EQ(qa.select, qb.select);
  EXPECT_EQ(qa.u.x, qb.u.x);
  EXPECT_EQ(qa.u.y, qb.u.y);
  EXPECT_NE(qa.select, qo.select);
  // Their other numbers come from their own streams (sample numbers differ).
  EXPECT_NE(a.uniform(), b.uniform());
}

TEST(PathRandom, LaterLightSamplesAreFreshDraws) {
  PathRandom r(1, 2, 3, 3);
  const LightUniforms first = r.light(), second = r.light();
  EXPECT_NE(first.select, second.select);
  EXPECT_GE(second.select, 0.0f);
  EXPECT_LT(second.select, 1.0f);
  EXPECT_EQ(PathRandom(1, 2, 3, 3).light().select, first.select);  // deterministic
}
