#include "triads/sdf.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/input_file.h"
#include "core/error.h"
#include "core/format.h"
#include "core/ray_check.h"

namespace inim {

namespace {

// Explicit little-endian encoding of 32-bit values, independent of the host's byte order.
void put32(unsigned char*& p, uint32_t u) {
  for (int b = 0; b < 4; ++b) *p++ = (unsigned char)(u >> (8 * b));
}
void putI(unsigned char*& p, int32_t v) { put32(p, uint32_t(v)); }
void putF(unsigned char*& p, float v) {
  uint32_t u;
  std::memcpy(&u, &v, 4);
  put32(p, u);
}
uint32_t get32(const unsigned char*& p) {
  uint32_t u = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  p += 4;
  return u;
}
int32_t getI(const unsigned char*& p) { return int32_t(get32(p)); }
float getF(const unsigned char*& p) {
  uint32_t u = get32(p);
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}

void encodeRays(const SdfRay* r, size_t n, unsigned char* out) {
  unsigned char* p = out;
  for (size_t i = 0; i < n; ++i) {
    putF(p, r[i].x), putF(p, r[i].y), putF(p, r[i].z);
    putF(p, r[i].l), putF(p, r[i].m), putF(p, r[i].n);
    putF(p, r[i].flux), putF(p, r[i].wavelengthUm);
  }
}

}  // namespace

void SdfHeader::setDescription(const std::string& s) {
  description.fill('\0');
  std::memcpy(description.data(), s.data(), std::min(s.size(), description.size() - 1));
}

std::string SdfHeader::descriptionText() const {
  size_t n = 0;
  while (n < description.size() && description[n] != '\0') ++n;
  return std::string(description.data(), n);
}

std::array<unsigned char, kSdfHeaderSize> encodeSdfHeader(const SdfHeader& h) {
  std::array<unsigned char, kSdfHeaderSize> b{};
  unsigned char* p = b.data();
  putI(p, h.identifier);
  put32(p, h.numRays);
  std::memcpy(p, h.description.data(), 100);
  p += 100;
  putF(p, h.sourceFlux), putF(p, h.raySetFlux), putF(p, h.wavelength);
  putF(p, h.inclinationBegin), putF(p, h.inclinationEnd), putF(p, h.azimuthBegin), putF(p, h.azimuthEnd);
  putI(p, h.dimensionUnits);
  for (float v : h.location) putF(p, v);
  for (float v : h.rotation) putF(p, v);
  for (float v : h.scale) putF(p, v);
  for (float v : h.unused) putF(p, v);
  putI(p, h.rayFormat);
  putI(p, h.fluxType);
  putI(p, h.reserved[0]), putI(p, h.reserved[1]);
  if (size_t(p - b.data()) != kSdfHeaderSize) throw std::logic_error("SDF header encoding is not 208 bytes");
  return b;
}

SdfHeader decodeSdfHeader(const unsigned char* bytes) {
  SdfHeader h;
  const unsigned char* p = bytes;
  h.identifier = getI(p);
  h.numRays = get32(p);
  std::memcpy(h.description.data(), p, 100);
  p += 100;
  h.sourceFlux = getF(p), h.raySetFlux = getF(p), h.wavelength = getF(p);
  h.inclinationBegin = getF(p), h.inclinationEnd = getF(p), h.azimuthBegin = getF(p), h.azimuthEnd = getF(p);
  h.dimensionUnits = getI(p);
  for (float& v : h.location) v = getF(p);
  for (float& v : h.rotation) v = getF(p);
  for (float& v : h.scale) v = getF(p);
  for (float& v : h.unused) v = getF(p);
  h.rayFormat = getI(p);
  h.fluxType = getI(p);
  h.reserved[0] = getI(p), h.reserved[1] = getI(p);
  return h;
}

// ---------------------------------------------------------------- writer

SdfWriter::SdfWriter(const std::string& path, const SdfHeader& header) : path_(path), header_(header) {
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw InputError(path, "", "", "a writable output file (" + std::string(std::strerror(errno)) + ")");
  header_.numRays = 0;
  auto b = encodeSdfHeader(header_);
  if (std::fwrite(b.data(), 1, b.size(), f_) != b.size())
    throw InputError(path_, "", "", "a writable output file (write failed)");
}

SdfWriter::~SdfWriter() {
  if (f_) std::fclose(f_);
}

void SdfWriter::write(const SdfRay* rays, size_t n) {
  if (!f_) throw std::logic_error("SdfWriter::write after finish");
  if (count_ + n > UINT32_MAX)
    throw InputError(path_, "", std::to_string(count_ + n) + " rays", "at most 4294967295 rays (uint32 count)");
  buf_.resize(n * kSdfRaySize);
  encodeRays(rays, n, buf_.data());
  if (n && std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size())
    throw InputError(path_, "", "", "a writable output file (write failed: disk full?)");
  for (size_t i = 0; i < n; ++i) fluxSum_ += rays[i].flux;
  count_ += n;
}

void SdfWriter::finish(bool raySetFluxIsSum) {
  if (!f_) return;
  header_.numRays = uint32_t(count_);
  if (raySetFluxIsSum) header_.raySetFlux = float(fluxSum_);
  auto b = encodeSdfHeader(header_);
  bool ok = std::fseek(f_, 0, SEEK_SET) == 0 && std::fwrite(b.data(), 1, b.size(), f_) == b.size();
  ok = (std::fclose(f_) == 0) && ok;
  f_ = nullptr;
  if (!ok) throw InputError(path_, "", "", "a writable output file (final header write failed)");
}

// ---------------------------------------------------------------- reader

SdfReader::SdfReader(const std::string& path) : path_(path) {
  std::error_code ec;
  uint64_t size = std::filesystem::file_size(path, ec);
  checkInputFile(path);
  f_ = ec ? nullptr : std::fopen(path.c_str(), "rb");
  if (!f_) throw InputError(path, "", "", "a readable Zemax source file (cannot open it)");
  try {  // a refused header must not leave the file open (the destructor does not run)
    unsigned char b[kSdfHeaderSize];
    if (size < kSdfHeaderSize || std::fread(b, 1, kSdfHeaderSize, f_) != kSdfHeaderSize)
      throw InputError(path, "", std::to_string(size) + " bytes", "a Zemax source file (208-byte header)");
    header_ = decodeSdfHeader(b);
    if (header_.identifier != kSdfIdentifier)
      throw InputError(path, "identifier", std::to_string(header_.identifier),
                       "1010 (a Zemax binary source file)");
    if (header_.rayFormat != kSdfFormatSpectral)
      throw InputError(path, "ray format", std::to_string(header_.rayFormat),
                       "2 (spectral: x y z l m n flux wavelength); flux-only files are not supported");
    uint64_t expected = kSdfHeaderSize + kSdfRaySize * uint64_t(header_.numRays);
    if (size != expected)
      throw InputError(path, "number of rays",
                       std::to_string(header_.numRays) + " rays in a file of " + std::to_string(size) + " bytes",
                       "file size 208 + 32 x rays = " + std::to_string(expected) +
                           " bytes (truncated or padded file)");
  } catch (...) {
    std::fclose(f_);
    f_ = nullptr;
    throw;
  }
}

SdfReader::~SdfReader() {
  if (f_) std::fclose(f_);
}

size_t SdfReader::read(SdfRay* out, size_t max) {
  size_t n = size_t(std::min<uint64_t>(max, header_.numRays - done_));
  if (n == 0) return 0;
  buf_.resize(n * kSdfRaySize);
  if (std::fread(buf_.data(), 1, buf_.size(), f_) != buf_.size())
    throw InputError(path_, "", "unexpected end of file", "a complete Zemax source file");
  const unsigned char* p = buf_.data();
  for (size_t i = 0; i < n; ++i) {
    SdfRay& r = out[i];
    r.x = getF(p), r.y = getF(p), r.z = getF(p);
    r.l = getF(p), r.m = getF(p), r.n = getF(p);
    r.flux = getF(p), r.wavelengthUm = getF(p);
    const std::string where = "ray " + std::to_string(done_ + i);
    checkRay(Vec3d(r.x, r.y, r.z), Vec3d(r.l, r.m, r.n), path_, where);
    if (!(r.flux >= 0.0f && std::isfinite(r.flux)) || !(r.wavelengthUm > 0.0f && r.wavelengthUm < 100.0f))
      throw InputError(path_, where, formatText("flux %.9g, wavelength %.9g um", r.flux, r.wavelengthUm),
                       "a finite flux >= 0 and a wavelength in (0, 100) um");
  }
  done_ += n;
  return n;
}

std::vector<SdfRay> readSdf(const std::string& path, SdfHeader* header) {
  SdfReader r(path);
  std::vector<SdfRay> rays(r.numRays());
  size_t got = 0;
  while (got < rays.size()) got += r.read(rays.data() + got, rays.size() - got);
  if (header) *header = r.header();
  return rays;
}

}  // namespace inim
