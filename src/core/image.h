#pragma once
// A float image with named channels, and reading/writing through OpenImageIO.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/large_buffer.h"

namespace inim {

struct Image {
  int width = 0, height = 0;
  std::vector<std::string> channels;  // e.g. {"R","G","B"} or {"R","G","B","A","Z"}
  std::vector<float> data;            // row-major, row 0 = top, channels interleaved

  Image() = default;
  Image(int w, int h, std::vector<std::string> ch)
      : width(w), height(h), channels(std::move(ch)), data(largeVector(size_t(w) * h * channels.size(), 0.0f)) {}
  int numChannels() const { return int(channels.size()); }
  float& at(int x, int y, int c) { return data[(size_t(y) * width + x) * channels.size() + c]; }
  float at(int x, int y, int c) const { return data[(size_t(y) * width + x) * channels.size() + c]; }
  int channelIndex(const std::string& name) const;  // -1 if absent
};

// Writes EXR (float) or PNG/JPEG/TIFF (8-bit, values in [0,1] already encoded) by extension.
// Throws std::runtime_error on failure.
void writeImage(const Image& img, const std::string& path);
// Named numbers kept in an EXR's header with the image (e.g. "inim:exposure", the factor an EIA
// was made with, which `inim view --reference` needs to expose its reference alike).
using ImageNumbers = std::vector<std::pair<std::string, double>>;
// EXR compression: zip (lossless) by default; none for images whose every mantissa is noise, which
// zip cannot shrink (a synthesized EIA: 4 % smaller for ~3 s of a core at 3840 x 1644).
enum class ExrCompression { Zip, None };
void writeImage(const Image& img, const std::string& path, const ImageNumbers& numbers,
                ExrCompression compression = ExrCompression::Zip);
// A number written so; nullopt when the file has no such header entry.
std::optional<double> readImageNumber(const std::string& path, const std::string& name);
// Reads any image OIIO knows. `rejectNonFinite`: throw InputError naming the file if any
// value is NaN or Inf.
Image readImage(const std::string& path, bool rejectNonFinite = true);

}  // namespace inim
