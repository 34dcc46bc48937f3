// The memory budget: sizes as people write them, the limit and its override, and requests
// whose byte counts would wrap an integer. Also the .npy reader's use of it: a declared shape is
// checked against the file and the budget before anything is allocated.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "core/npy.h"
#include "core/size_budget.h"
#include "expect_input_error.h"
#include "scratch_dir.h"

using namespace inim;

namespace {

constexpr uint64_t kKiB = 1024, kMiB = kKiB * 1024, kGiB = kMiB * 1024;

ScratchDir scratch("size_budget");

// An .npy header (format 1.0, '<f4') declaring `shape`, followed by `dataBytes` zero bytes.
std::string writeNpyHeader(const std::string& name, const std::string& shape, size_t dataBytes) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
  header.append(64 - (10 + header.size() + 1) % 64, ' ');
  header += '\n';
  const std::string path = scratch.path(name);
  std::ofstream f(path, std::ios::binary);
  f.write("\x93NUMPY\x01\x00", 8);
  const uint16_t len = uint16_t(header.size());
  f.write(reinterpret_cast<const char*>(&len), 2);
  f << header << std::string(dataBytes, '\0');
  return path;
}

}  // namespace

TEST(SizeBudget, ParsesSizesInPowersOf1024) {
  EXPECT_EQ(parseByteSize("8G", "--max-memory"), 8 * kGiB);
  EXPECT_EQ(parseByteSize("8GiB", "--max-memory"), 8 * kGiB);
  EXPECT_EQ(parseByteSize("8gb", "--max-memory"), 8 * kGiB);
  EXPECT_EQ(parseByteSize("512M", "--max-memory"), 512 * kMiB);
  EXPECT_EQ(parseByteSize("1.5k", "--max-memory"), 1536u);
  EXPECT_EQ(parseByteSize("2T", "--max-memory"), 2048 * kGiB);
  EXPECT_EQ(parseByteSize("2e9", "--max-memory"), 2000000000u);
  EXPECT_EQ(parseByteSize("4096", "--max-memory"), 4096u);
}

TEST(SizeBudget, RefusesSizesThatAreNotSizes) {
  for (const char* text : {"", "G", "abc", "0", "-1G", "8X", "8GG", "nan", "inf", "1e30"}) {
    const InputError e = expectInputError([&] { parseByteSize(text, "--max-memory"); });
    EXPECT_EQ(e.key(), "--max-memory") << text;
    EXPECT_NE(e.value().find(text), std::string::npos) << text;
  }
}

TEST(SizeBudget, DefaultIsAtMost16GiBAndScopedLimitsRestoreIt) {
  const uint64_t before = memoryLimitBytes();
  EXPECT_GT(defaultMemoryLimitBytes(), 0u);
  EXPECT_LE(defaultMemoryLimitBytes(), 16 * kGiB);
  {
    ScopedMemoryLimit limit(kMiB);
    EXPECT_EQ(memoryLimitBytes(), kMiB);
  }
  EXPECT_EQ(memoryLimitBytes(), before);
}

TEST(SizeBudget, RequestsUpToTheLimitPassAndBeyondItNameSettingSizeAndLimit) {
  ScopedMemoryLimit limit(kMiB);
  EXPECT_NO_THROW(checkAllocation("", "width/height", "512 x 512", {{512.0 * 512.0, 4.0}}, "the image"));
  const InputError e = expectInputError(
      [] { checkAllocation("scene.json", "width/height", "512 x 513", {{512.0 * 513.0, 4.0}}, "the image"); });
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(e.key(), "width/height");
  EXPECT_EQ(e.value(), "512 x 513");
  EXPECT_NE(e.expected().find("the image needs 1 MiB"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("limit of 1 MiB"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("--max-memory"), std::string::npos) << e.what();
  // Terms add up: two halves of the limit fit, a byte more does not.
  EXPECT_NO_THROW(checkAllocation("", "k", "v", {{kMiB / 2.0, 1.0}, {kMiB / 2.0, 1.0}}, "both"));
  EXPECT_THROW(checkAllocation("", "k", "v", {{kMiB / 2.0, 1.0}, {kMiB / 2.0 + 1.0, 1.0}}, "both"), InputError);
}

TEST(SizeBudget, ProductsThatWouldWrapAreRefusedNotWrapped) {
  ScopedMemoryLimit limit(16 * kGiB);
  // 2^32 x 2^32 x 1 byte wraps a 64-bit count to 0.
  const double n = 4294967296.0;
  EXPECT_THROW(checkAllocation("", "k", "v", {{n * n, 1.0}}, "a square"), InputError);
  EXPECT_THROW(checkAllocation("", "k", "v", {{1e300 * 1e300, 1.0}}, "infinity"), InputError);
  EXPECT_EQ(allocationBytes({{-5.0, 4.0}, {3.0, 4.0}}), 12.0);
}

TEST(SizeBudget, FormatsBytesForPeople) {
  EXPECT_EQ(formatBytes(512), "512 B");
  EXPECT_EQ(formatBytes(1024), "1 KiB");
  EXPECT_EQ(formatBytes(1.5 * kGiB), "1.5 GiB");
  EXPECT_EQ(formatBytes(12.0 * 1024 * kGiB), "12 TiB");
}

TEST(SizeBudget, NpyShapeBeyondTheFileIsRefusedBeforeAllocating) {
  // 10^12 x 3 floats (12 TB) declared in a file of 64 data bytes.
  const std::string p = writeNpyHeader("huge.npy", "(1000000000000, 3)", 64);
  const InputError e = expectInputError([&] { readNpy(p); });
  EXPECT_EQ(e.file(), p);
  EXPECT_EQ(e.key(), "data");
  EXPECT_NE(e.value().find("64 B"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("(1000000000000, 3)"), std::string::npos) << e.what();
}

TEST(SizeBudget, NpyNegativeOrMalformedDimensionsAreRefused) {
  // Once read as (25000, 3): the minus sign was dropped.
  for (const char* shape : {"(25000, -3)", "(-1,)", "(2.5, 3)", "(99999999999999999999, 3)"}) {
    const std::string p = writeNpyHeader("neg.npy", shape, 25000 * 3 * 4);
    const InputError e = expectInputError([&] { readNpy(p); });
    EXPECT_EQ(e.key(), "shape") << shape;
  }
}

TEST(SizeBudget, NpyShapeWithinTheFileButBeyondTheBudgetIsRefused) {
  const std::string p = writeNpyHeader("big.npy", "(1000, 3)", 12000);
  {
    ScopedMemoryLimit limit(8 * kKiB);
    const InputError e = expectInputError([&] { readNpy(p); });
    EXPECT_EQ(e.key(), "shape");
    EXPECT_NE(e.expected().find("--max-memory"), std::string::npos) << e.what();
  }
  const NpyArray a = readNpy(p);  // the default limit takes it
  EXPECT_EQ(a.rows, 1000);
  EXPECT_EQ(a.cols, 3);
}
