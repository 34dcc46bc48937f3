// Reading and writing the versioned VoxelGrid model file.
#include "radiance/grid_io.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/input_file.h"
#include "core/error.h"

namespace inim {
namespace {

static_assert(std::endian::native == std::endian::little, "the model format is little-endian");

constexpr char kMagic[8] = {'I', 'N', 'I', 'M', 'R', 'F', 'G', '\0'};

struct Header {
  float lo[3], hi[3];
  int32_t res[3];
  int32_t shDegree;
  uint32_t activation;
  float background[3];
  float densityScale;
  uint64_t checksum;
};

uint64_t fnv1a(const void* data, size_t bytes, uint64_t h = 0xcbf29ce484222325ull) {
  // Word-wise FNV-1a: fast enough for hundreds of MB, catches flipped or shifted data.
  const auto* p = static_cast<const unsigned char*>(data);
  size_t words = bytes / 8;
  for (size_t i = 0; i < words; ++i) {
    uint64_t w;
    std::memcpy(&w, p + 8 * i, 8);
    h = (h ^ w) * 0x100000001b3ull;
  }
  for (size_t i = words * 8; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

uint64_t payloadChecksum(const VoxelGrid& g) {
  uint64_t h = fnv1a(g.density.data(), g.density.size() * sizeof(float));
  return fnv1a(g.color.data(), g.color.size() * sizeof(float), h);
}

[[noreturn]] void bad(const std::string& path, const std::string& value) {
  throw InputError(path, "header", value,
                   "an inim radiance-field model (magic INIMRFG, version <= " +
                       std::to_string(kVoxelGridVersion) + ")");
}

}  // namespace

void saveVoxelGrid(const VoxelGrid& g, const std::string& path) {
  Header h{};
  for (int a = 0; a < 3; ++a) {
    h.lo[a] = g.lo[a];
    h.hi[a] = g.hi[a];
    h.res[a] = g.res[a];
    h.background[a] = g.background[a];
  }
  h.shDegree = g.shDegree;
  h.activation = uint32_t(g.activation);
  h.densityScale = g.densityScale;
  h.checksum = payloadChecksum(g);
  std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "path", path, "a writable file");
    const uint32_t metaBytes = uint32_t(g.metadata.size());
    uint32_t version = kVoxelGridVersion, headerBytes = uint32_t(sizeof(Header)) + 4 + metaBytes;
    out.write(kMagic, 8);
    out.write(reinterpret_cast<const char*>(&version), 4);
    out.write(reinterpret_cast<const char*>(&headerBytes), 4);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.write(reinterpret_cast<const char*>(&metaBytes), 4);
    out.write(g.metadata.data(), std::streamsize(metaBytes));
    out.write(reinterpret_cast<const char*>(g.density.data()), std::streamsize(g.density.size() * 4));
    out.write(reinterpret_cast<const char*>(g.color.data()), std::streamsize(g.color.size() * 4));
    if (!out.flush()) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw InputError(path, "path", path, "a writable file (write failed)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "path", path, "a writable file (rename failed)");
  }
}

VoxelGrid loadVoxelGrid(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "path", path, "an existing, readable model file");
  in.seekg(0, std::ios::end);
  uint64_t fileSize = uint64_t(in.tellg());
  in.seekg(0);
  char magic[8] = {};
  uint32_t version = 0, headerBytes = 0;
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) bad(path, "not an inim model");
  if (!in.read(reinterpret_cast<char*>(&version), 4) || !in.read(reinterpret_cast<char*>(&headerBytes), 4))
    bad(path, "truncated header");
  if (version == 0 || version > kVoxelGridVersion)
    bad(path, "format version " + std::to_string(version));
  if (headerBytes < sizeof(Header) || headerBytes > (1u << 20))
    bad(path, "header size " + std::to_string(headerBytes));
  Header h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) bad(path, "truncated header");
  VoxelGrid g;
  // The metadata string follows the fixed header when there is room for it.
  if (headerBytes >= sizeof(Header) + 4) {
    uint32_t metaBytes = 0;
    if (!in.read(reinterpret_cast<char*>(&metaBytes), 4) || metaBytes > headerBytes - sizeof(Header) - 4)
      bad(path, "corrupt metadata length");
    g.metadata.resize(metaBytes);
    if (!in.read(g.metadata.data(), std::streamsize(metaBytes))) bad(path, "truncated metadata");
  }
  in.seekg(std::streamoff(16 + headerBytes));

  bool ok = h.shDegree >= 0 && h.shDegree <= 2 && h.activation <= 1 && std::isfinite(h.densityScale) &&
            h.densityScale > 0.0f;
  for (int a = 0; a < 3; ++a) {
    ok = ok && std::isfinite(h.lo[a]) && std::isfinite(h.hi[a]) && h.lo[a] < h.hi[a] &&
         h.res[a] >= 2 && h.res[a] <= 8192 && std::isfinite(h.background[a]);
    g.lo[a] = h.lo[a];
    g.hi[a] = h.hi[a];
    g.res[a] = h.res[a];
    g.background[a] = h.background[a];
  }
  if (!ok) bad(path, "corrupt header");
  g.shDegree = h.shDegree;
  g.activation = DensityActivation(h.activation);
  g.densityScale = h.densityScale;
  uint64_t n = g.vertexCount(), floats = n * (1 + uint64_t(g.colorStride()));
  if (fileSize != 16 + uint64_t(headerBytes) + floats * 4)
    bad(path, std::to_string(fileSize) + " bytes, expected " +
                  std::to_string(16 + uint64_t(headerBytes) + floats * 4) + " (truncated or corrupt)");
  g.density.resize(n);
  g.color.resize(n * size_t(g.colorStride()));
  if (!in.read(reinterpret_cast<char*>(g.density.data()), std::streamsize(n * 4)) ||
      !in.read(reinterpret_cast<char*>(g.color.data()), std::streamsize(g.color.size() * 4)))
    bad(path, "truncated data");
  if (payloadChecksum(g) != h.checksum) bad(path, "checksum mismatch (corrupt data)");
  return g;
}

}  // namespace inim
