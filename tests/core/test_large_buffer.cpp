// largeVector (src/core/large_buffer.h): the same vector std::vector(n, value) makes, large or
// small, whatever the kernel does with the advice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

#include "core/large_buffer.h"

using namespace inim;

TEST(LargeBuffer, HoldsNCopiesOfTheValue) {
  for (size_t n : {size_t(0), size_t(1), size_t(1000), size_t(3) << 20}) {  // up to 12 MiB of floats
    const std::vector<float> v = largeVector(n, 0.25f);
    ASSERT_EQ(v.size(), n);
    EXPECT_TRUE(std::all_of(v.begin(), v.end(), [](float x) { return x == 0.25f; }));
  }
  const std::vector<uint8_t> flags = largeVector(size_t(5) << 20, uint8_t(0));
  EXPECT_EQ(std::count(flags.begin(), flags.end(), uint8_t(0)), ptrdiff_t(5) << 20);
}

TEST(LargeBuffer, AdviceOnAnyRangeIsHarmless) {
  std::vector<char> small(100, 'x');
  adviseHugePages(small.data(), small.size());  // spans no whole huge page: nothing to advise
  adviseHugePages(nullptr, size_t(64) << 20);
  EXPECT_EQ(std::count(small.begin(), small.end(), 'x'), 100);
}
