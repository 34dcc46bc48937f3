#include "rays/ray_binary.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/input_file.h"
#include "core/error.h"
#include "core/size_budget.h"

namespace inim {

namespace {

static_assert(sizeof(float) == 4 && sizeof(uint32_t) == 4, "32-bit float and int required");

template <class T>
void putLE(unsigned char* p, T v) {
  uint64_t u = 0;
  std::memcpy(&u, &v, sizeof(T));
  for (size_t b = 0; b < sizeof(T); ++b) p[b] = (unsigned char)(u >> (8 * b));
}
template <class T>
T getLE(const unsigned char* p) {
  uint64_t u = 0;
  for (size_t b = 0; b < sizeof(T); ++b) u |= uint64_t(p[b]) << (8 * b);
  T v;
  std::memcpy(&v, &u, sizeof(T));
  return v;
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};

// Arrays of float32 in file order; byte-swapped on big-endian hosts.
void writeFloats(std::FILE* f, const std::vector<float>& v, const std::string& path) {
  if constexpr (std::endian::native == std::endian::little) {
    if (!v.empty() && std::fwrite(v.data(), sizeof(float), v.size(), f) != v.size())
      throw InputError(path, "", "", "a writable output file (write failed: disk full?)");
  } else {
    std::vector<unsigned char> buf(v.size() * 4);
    for (size_t i = 0; i < v.size(); ++i) putLE(&buf[i * 4], v[i]);
    if (std::fwrite(buf.data(), 1, buf.size(), f) != buf.size())
      throw InputError(path, "", "", "a writable output file (write failed: disk full?)");
  }
}

void readFloats(std::FILE* f, std::vector<float>& v, const std::string& path) {
  if (!v.empty() && std::fread(v.data(), sizeof(float), v.size(), f) != v.size())
    throw InputError(path, "", "truncated ray data", "a complete inim binary ray file");
  if constexpr (std::endian::native != std::endian::little)
    for (float& x : v) x = getLE<float>(reinterpret_cast<const unsigned char*>(&x));
}

constexpr char kMagic[8] = {'I', 'N', 'I', 'M', 'R', 'A', 'Y', 'S'};

}  // namespace

void writeRayBinary(const std::string& path, const RaySet& rays, const RayBinaryInfo& info) {
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "wb"));
  if (!f) throw InputError(path, "", "", "a writable output file (" + std::string(std::strerror(errno)) + ")");
  unsigned char h[kRayBinaryHeaderSize] = {};
  std::memcpy(h, kMagic, 8);
  putLE<uint32_t>(h + 8, kRayBinaryVersion);
  putLE<uint32_t>(h + 12, kRayBinaryHeaderSize);
  putLE<uint64_t>(h + 16, uint64_t(rays.size()));
  putLE<int32_t>(h + 24, info.eiCols);
  putLE<int32_t>(h + 28, info.eiRows);
  putLE<int32_t>(h + 32, info.eiW);
  putLE<int32_t>(h + 36, info.eiH);
  putLE<float>(h + 40, info.gapMm);
  putLE<uint32_t>(h + 44, 0);
  if (std::fwrite(h, 1, sizeof h, f.get()) != sizeof h)
    throw InputError(path, "", "", "a writable output file (write failed)");
  for (const auto* v : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) writeFloats(f.get(), *v, path);
  if (std::fflush(f.get()) != 0) throw InputError(path, "", "", "a writable output file (flush failed)");
}

namespace {

// A NaN or infinite origin or direction would pass through every later stage into the outputs.

}  // namespace

RaySet readRayBinary(const std::string& path, RayBinaryInfo* info) {
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  checkInputFile(path);
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (ec || !f) throw InputError(path, "", "", "a readable inim binary ray file (cannot open it)");
  unsigned char h[kRayBinaryHeaderSize];
  if (size < kRayBinaryHeaderSize || std::fread(h, 1, sizeof h, f.get()) != sizeof h)
    throw InputError(path, "", std::to_string(size) + " bytes", "an inim binary ray file (48-byte header)");
  if (std::memcmp(h, kMagic, 8) != 0)
    throw InputError(path, "magic", "\"" + std::string(reinterpret_cast<char*>(h), 8) + "\"",
                     "\"INIMRAYS\" (an inim binary ray file)");
  uint32_t version = getLE<uint32_t>(h + 8), hsize = getLE<uint32_t>(h + 12);
  if (version != kRayBinaryVersion)
    throw InputError(path, "version", std::to_string(version), std::to_string(kRayBinaryVersion));
  if (hsize != kRayBinaryHeaderSize)
    throw InputError(path, "header size", std::to_string(hsize), std::to_string(kRayBinaryHeaderSize));
  uint64_t n = getLE<uint64_t>(h + 16);
  if (n > (size - kRayBinaryHeaderSize) / 24 || kRayBinaryHeaderSize + 24 * n != size)
    throw InputError(path, "ray count", std::to_string(n) + " rays in a file of " + std::to_string(size) + " bytes",
                     "file size 48 + 24 x count = " + std::to_string(kRayBinaryHeaderSize + 24 * n) +
                         " bytes (truncated or padded file)");
  if (info) {
    info->eiCols = getLE<int32_t>(h + 24);
    info->eiRows = getLE<int32_t>(h + 28);
    info->eiW = getLE<int32_t>(h + 32);
    info->eiH = getLE<int32_t>(h + 36);
    info->gapMm = getLE<float>(h + 40);
  }
  checkAllocation(path, "ray count", std::to_string(n), {{double(n), 24.0}}, "the rays");
  RaySet rays;
  rays.resize(size_t(n));
  for (auto* v : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) readFloats(f.get(), *v, path);
  checkRays(rays, path);
  return rays;
}

}  // namespace inim
