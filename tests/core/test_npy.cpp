#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "core/npy.h"
#include "expect_input_error.h"
#include "scratch_dir.h"

using namespace inim;

namespace {
ScratchDir scratch("npy");

// An .npy file written byte by byte as numpy.save writes it (format 1.0, '<f8', shape (2, 3)).
void writeNumpyStyle(const std::string& path, const std::string& descr, const std::string& order,
                     const std::string& shape, const std::vector<double>& values) {
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + order + ", 'shape': " + shape + ", }";
  header.append(64 - (10 + header.size() + 1) % 64, ' ');
  header += '\n';
  std::ofstream f(path, std::ios::binary);
  f.write("\x93NUMPY\x01\x00", 8);
  const uint16_t len = uint16_t(header.size());
  f.write(reinterpret_cast<const char*>(&len), 2);
  f << header;
  f.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 8));
}
}  // namespace

TEST(Npy, RoundTripKeepsShapeAndValuesAndAlignsHeader) {
  NpyArray a;
  a.rows = 3, a.cols = 8;
  for (int i = 0; i < 24; ++i) a.data.push_back(float(i) * 0.25f - 1.0f);
  a.data[5] = std::numeric_limits<float>::infinity();  // far = inf is a legal ray-table value
  const std::string p = scratch.path("a.npy");
  writeNpy(p, a);
  std::ifstream f(p, std::ios::binary | std::ios::ate);
  const auto size = size_t(f.tellg());
  EXPECT_EQ((size - 24 * 4) % 64, 0u);  // data starts on a 64-byte boundary, as numpy writes it
  NpyArray b = readNpy(p);
  EXPECT_EQ(b.rows, 3);
  EXPECT_EQ(b.cols, 8);
  EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size() * 4));
}

TEST(Npy, ReadsFloat64AndOneDimensionalArrays) {
  const std::string p = scratch.path("f8.npy");
  writeNumpyStyle(p, "<f8", "False", "(2, 3)", {1, 2, 3, 4, 5, 6.5});
  NpyArray a = readNpy(p);
  EXPECT_EQ(a.rows, 2);
  EXPECT_EQ(a.cols, 3);
  EXPECT_FLOAT_EQ(a.at(1, 2), 6.5f);
  const std::string q = scratch.path("v.npy");
  writeNumpyStyle(q, "<f8", "False", "(4,)", {1, 2, 3, 4});
  NpyArray v = readNpy(q);
  EXPECT_EQ(v.rows, 4);
  EXPECT_EQ(v.cols, 1);
}

TEST(Npy, ForeignOrUnsupportedFilesAreInputErrors) {
  const std::string p = scratch.path("int.npy");
  writeNumpyStyle(p, "<i8", "False", "(2, 3)", {1, 2, 3, 4, 5, 6});
  EXPECT_EQ(expectInputError([&] { readNpy(p); }).key(), "descr");
  const std::string q = scratch.path("fortran.npy");
  writeNumpyStyle(q, "<f8", "True", "(2, 3)", {1, 2, 3, 4, 5, 6});
  EXPECT_EQ(expectInputError([&] { readNpy(q); }).key(), "fortran_order");
  const std::string r = scratch.path("short.npy");
  writeNumpyStyle(r, "<f8", "False", "(2, 3)", {1, 2, 3});
  EXPECT_EQ(expectInputError([&] { readNpy(r); }).key(), "data");
  const std::string t = scratch.path("text.npy");
  std::ofstream(t) << "not numpy";
  EXPECT_EQ(expectInputError([&] { readNpy(t); }).key(), "magic");
}
