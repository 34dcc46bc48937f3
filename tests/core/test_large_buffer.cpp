// largeVector (src/core/large_buffer.h): the same vector std::vector(n, value) makes, on memory
// the kernel has been asked to back with huge pages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "core/large_buffer.h"

using namespace inim;

namespace {

// The VmFlags of the mapping holding `p` in /proc/self/smaps ("" when not found).
std::string vmFlagsOf(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const uintptr_t a = reinterpret_cast<uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-') inside = lo <= a && a < hi;
    else if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

bool kernelOffersHugePages() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(f, modes);
  return !modes.empty() && modes.find("[never]") == std::string::npos;
}

}  // namespace

TEST(LargeBuffer, HoldsNCopiesOfTheValue) {
  for (size_t n : {size_t(0), size_t(1), size_t(1000), size_t(3) << 20}) {  // up to 12 MiB of floats
    const std::vector<float> v = largeVector(n, 0.25f);
    ASSERT_EQ(v.size(), n);
    EXPECT_TRUE(std::all_of(v.begin(), v.end(), [](float x) { return x == 0.25f; }));
  }
  const std::vector<uint8_t> flags = largeVector(size_t(5) << 20, uint8_t(0));
  EXPECT_EQ(std::count(flags.begin(), flags.end(), uint8_t(0)), ptrdiff_t(5) << 20);
}

// The advice reaches the kernel: a 32 MiB buffer's mapping carries the "hg" flag (MADV_HUGEPAGE).
TEST(LargeBuffer, LargeBuffersAreAdvisedOntoHugePages) {
  if (!kernelOffersHugePages()) GTEST_SKIP() << "transparent huge pages are off on this kernel";
  const std::vector<float> v = largeVector(size_t(8) << 20, 1.0f);
  const std::string flags = vmFlagsOf(v.data() + v.size() / 2);
  ASSERT_FALSE(flags.empty()) << "no mapping found in /proc/self/smaps";
  EXPECT_NE((flags + " ").find(" hg "), std::string::npos) << flags;
}
