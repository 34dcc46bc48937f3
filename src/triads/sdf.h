#pragma once
// The Zemax OpticStudio binary source file (.SDF, spectral ray format), docs/design.md.
// Little-endian, a 208-byte header, then 32 bytes a ray: float32 x y z l m n flux
// wavelength_um. Written with fixed-width types and explicit little-endian byte order (the
// paper's writer used a C "long", which is 8 bytes on Linux and broke its header).
#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace inim {

constexpr int32_t kSdfIdentifier = 1010;
constexpr int32_t kSdfUnitsMm = 4;
constexpr int32_t kSdfFormatSpectral = 2;
constexpr int32_t kSdfFluxWatts = 0;
constexpr size_t kSdfHeaderSize = 208;
constexpr size_t kSdfRaySize = 32;

struct SdfHeader {
  int32_t identifier = kSdfIdentifier;
  uint32_t numRays = 0;
  std::array<char, 100> description{};  // NUL-padded
  float sourceFlux = 1.0f;
  float raySetFlux = 1.0f;
  float wavelength = 0.0f;  // 0: every ray carries its own (spectral format)
  float inclinationBegin = 0.0f, inclinationEnd = 0.0f;
  float azimuthBegin = 0.0f, azimuthEnd = 0.0f;
  int32_t dimensionUnits = kSdfUnitsMm;
  std::array<float, 3> location{}, rotation{}, scale{};  // zeros, as the paper's code wrote
  std::array<float, 4> unused{};
  int32_t rayFormat = kSdfFormatSpectral;
  int32_t fluxType = kSdfFluxWatts;
  std::array<int32_t, 2> reserved{};

  void setDescription(const std::string& s);  // truncated to 99 characters
  std::string descriptionText() const;
};
// The in-memory struct has the file's layout (no padding); I/O still goes field by field.
static_assert(sizeof(SdfHeader) == kSdfHeaderSize, "Zemax SDF header must be 208 bytes");

struct SdfRay {
  float x, y, z, l, m, n, flux, wavelengthUm;
};
static_assert(sizeof(SdfRay) == kSdfRaySize, "Zemax SDF ray must be 32 bytes");

std::array<unsigned char, kSdfHeaderSize> encodeSdfHeader(const SdfHeader& h);
SdfHeader decodeSdfHeader(const unsigned char* bytes);

// Streams rays to an SDF file; the ray count in the header is patched by finish().
class SdfWriter {
 public:
  // Throws InputError naming the path when it cannot be written.
  SdfWriter(const std::string& path, const SdfHeader& header);
  ~SdfWriter();
  SdfWriter(const SdfWriter&) = delete;
  SdfWriter& operator=(const SdfWriter&) = delete;
  void write(const SdfRay* rays, size_t n);
  void write(const std::vector<SdfRay>& rays) { write(rays.data(), rays.size()); }
  // Writes the final header (count, and ray-set flux = sum of fluxes if asked) and closes.
  void finish(bool raySetFluxIsSum = false);
  uint64_t count() const { return count_; }
  double fluxSum() const { return fluxSum_; }

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  SdfHeader header_;
  uint64_t count_ = 0;
  double fluxSum_ = 0.0;
  std::vector<unsigned char> buf_;
};

// Reads an SDF file in chunks after validating identifier, ray format and file size
// (208 + 32 N); InputError naming the file otherwise.
class SdfReader {
 public:
  explicit SdfReader(const std::string& path);
  ~SdfReader();
  SdfReader(const SdfReader&) = delete;
  SdfReader& operator=(const SdfReader&) = delete;
  const SdfHeader& header() const { return header_; }
  uint64_t numRays() const { return header_.numRays; }
  size_t read(SdfRay* out, size_t max);  // returns the number read, 0 at the end

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  SdfHeader header_;
  uint64_t done_ = 0;
  std::vector<unsigned char> buf_;
};

std::vector<SdfRay> readSdf(const std::string& path, SdfHeader* header = nullptr);

}  // namespace inim
