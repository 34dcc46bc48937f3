#include "core/npy.h"

#include <cstring>
#include <fstream>
#include <regex>
#include <stdexcept>

#include "core/input_file.h"
#include "core/error.h"
#include "core/size_budget.h"

namespace inim {

namespace {
const char kMagic[] = "\x93NUMPY";

// The dimensions of a shape tuple "(25000, 3)": whole numbers >= 0 (a minus sign is not
// dropped, a number beyond int64 is not wrapped).
std::vector<int64_t> parseShape(const std::string& path, const std::string& dims) {
  std::vector<int64_t> shape;
  const std::regex item("\\s*([^,\\s][^,]*?)\\s*(,|$)");
  for (std::sregex_iterator it(dims.begin(), dims.end(), item), end; it != end; ++it) {
    const std::string text = (*it)[1];
    if (text.empty()) continue;
    size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || v < 0)
      throw InputError(path, "shape", "(" + dims + ")", "dimensions that are whole numbers >= 0");
    shape.push_back(v);
  }
  return shape;
}

// The data a shape declares must be in the file, and within the memory budget, before any of it
// is allocated: a header claiming (1e12, 3) once asked for 12 TB.
void checkDeclaredSize(std::ifstream& f, const std::string& path, const std::string& dims, double count,
                       size_t itemSize) {
  const std::streampos dataStart = f.tellg();
  f.seekg(0, std::ios::end);
  const double available = double(f.tellg() - dataStart);
  f.seekg(dataStart);
  const double declared = count * double(itemSize);
  if (declared > available)
    throw InputError(path, "data", "truncated: " + formatBytes(available) + " after the header",
                     "the " + formatBytes(declared) + " of data of shape (" + dims + ")");
  checkAllocation(path, "shape", "(" + dims + ")", {{count, double(sizeof(float))}, {itemSize == 8 ? count : 0.0, 8.0}},
                  "the array");
}

}  // namespace

void writeNpy(const std::string& path, const NpyArray& a) {
  if (a.data.size() != size_t(a.rows * a.cols)) throw std::runtime_error("writeNpy: data size does not match shape");
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(a.rows) + ", " +
                       std::to_string(a.cols) + "), }";
  // Magic (6) + version (2) + length (2) + header + '\n' is a multiple of 64.
  const size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::ofstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.write(kMagic, 6);
  const char version[2] = {1, 0};
  f.write(version, 2);
  const uint16_t len = uint16_t(header.size());
  const unsigned char lenBytes[2] = {static_cast<unsigned char>(len & 0xFF), static_cast<unsigned char>(len >> 8)};
  f.write(reinterpret_cast<const char*>(lenBytes), 2);
  f.write(header.data(), std::streamsize(header.size()));
  // float32 little-endian: the host order on every machine inim builds for (x86-64, arm64).
  f.write(reinterpret_cast<const char*>(a.data.data()), std::streamsize(a.data.size() * sizeof(float)));
  if (!f) throw std::runtime_error("cannot write " + path);
}

NpyArray readNpy(const std::string& path) {
  checkInputFile(path);
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "file", "\"" + path + "\"", "a readable .npy file");
  char magic[6] = {};
  unsigned char version[2] = {};
  f.read(magic, 6);
  f.read(reinterpret_cast<char*>(version), 2);
  if (!f || std::memcmp(magic, kMagic, 6) != 0)
    throw InputError(path, "magic", "not \\x93NUMPY", "a NumPy .npy file");
  uint32_t len = 0;
  if (version[0] == 1) {
    unsigned char b[2] = {};
    f.read(reinterpret_cast<char*>(b), 2);
    len = uint32_t(b[0]) | uint32_t(b[1]) << 8;
  } else if (version[0] == 2 || version[0] == 3) {
    unsigned char b[4] = {};
    f.read(reinterpret_cast<char*>(b), 4);
    len = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
  } else {
    throw InputError(path, "version", std::to_string(version[0]) + "." + std::to_string(version[1]),
                     "NumPy format 1.0, 2.0 or 3.0");
  }
  if (!f || len > (1u << 20)) throw InputError(path, "header", "truncated", "a NumPy .npy header");
  std::string header(len, '\0');
  f.read(header.data(), len);
  if (!f) throw InputError(path, "header", "truncated", "a NumPy .npy header");

  std::smatch m;
  if (!std::regex_search(header, m, std::regex("'descr'\\s*:\\s*'([^']*)'")))
    throw InputError(path, "descr", "missing", "a dtype");
  const std::string descr = m[1];
  size_t itemSize = 0;
  if (descr == "<f4") itemSize = 4;
  else if (descr == "<f8") itemSize = 8;
  else throw InputError(path, "descr", "'" + descr + "'", "little-endian float32 or float64 ('<f4' or '<f8')");
  if (std::regex_search(header, m, std::regex("'fortran_order'\\s*:\\s*True")))
    throw InputError(path, "fortran_order", "True", "C order (numpy.ascontiguousarray before saving)");
  if (!std::regex_search(header, m, std::regex("'shape'\\s*:\\s*\\(([^)]*)\\)")))
    throw InputError(path, "shape", "missing", "a shape");
  const std::string dims = m[1];
  const std::vector<int64_t> shape = parseShape(path, dims);
  NpyArray a;
  if (shape.size() == 1) a.rows = shape[0], a.cols = 1;
  else if (shape.size() == 2) a.rows = shape[0], a.cols = shape[1];
  else throw InputError(path, "shape", "(" + dims + ")", "a 1-D or 2-D array");
  checkDeclaredSize(f, path, dims, double(a.rows) * double(a.cols), itemSize);

  const size_t n = size_t(a.rows * a.cols);
  a.data.resize(n);
  if (itemSize == 4) {
    f.read(reinterpret_cast<char*>(a.data.data()), std::streamsize(n * 4));
  } else {
    std::vector<double> d(n);
    f.read(reinterpret_cast<char*>(d.data()), std::streamsize(n * 8));
    for (size_t i = 0; i < n; ++i) a.data[i] = float(d[i]);
  }
  if (!f) throw InputError(path, "data", "truncated", std::to_string(n) + " values of shape (" + dims + ")");
  return a;
}

}  // namespace inim
