#pragma once
// NumPy .npy arrays (format versions 1.0-3.0): the exchange format Python tools read with
// numpy.load and write with numpy.save. inim reads and writes 2-D little-endian float arrays
// in C order, which is what ray and colour tables are.
#include <cstdint>
#include <string>
#include <vector>

namespace inim {

struct NpyArray {
  int64_t rows = 0, cols = 0;  // shape (rows, cols); a 1-D array reads as (n, 1)
  std::vector<float> data;     // row-major
  float at(int64_t r, int64_t c) const { return data[size_t(r * cols + c)]; }
};

// Writes a (rows, cols) float32 array, format 1.0 (header padded to 64 bytes). Throws
// std::runtime_error when the file cannot be written.
void writeNpy(const std::string& path, const NpyArray& a);

// Reads a 1-D or 2-D array of dtype <f4 or <f8 (converted to float) in C order. InputError
// naming the file and the header field for anything else (not an .npy file, Fortran order,
// big-endian or integer dtype, 3-D shape, truncated data).
NpyArray readNpy(const std::string& path);

}  // namespace inim
