#include "core/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "core/input_file.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/quiet_stderr.h"
#include "core/size_budget.h"
#include "core/file_kinds.h"

namespace inim {

namespace {

// OIIO's error text on one line ("a\nb\n" -> "a; b").
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) text.replace(at, 1, "; ");
  return text;
}

}  // namespace

int Image::channelIndex(const std::string& name) const {
  auto it = std::find(channels.begin(), channels.end(), name);
  return it == channels.end() ? -1 : int(it - channels.begin());
}

namespace {

// Writes the pixels in bands of rows, polling for Ctrl-C between bands so that a large
// image's write stops promptly (the caller's OutputSet removes the partial file).
bool writeRowBands(OIIO::ImageOutput& out, int width, int height, int channels, OIIO::TypeDesc type,
                   const void* pixels) {
  constexpr int kBandRows = 128;  // a multiple of EXR's zip block (16 rows)
  const size_t rowBytes = size_t(width) * size_t(channels) * type.size();
  for (int y = 0; y < height; y += kBandRows) {
    throwIfInterrupted();
    const int y1 = std::min(height, y + kBandRows);
    if (!out.write_scanlines(y, y1, 0, type, static_cast<const char*>(pixels) + size_t(y) * rowBytes)) return false;
  }
  return true;
}

std::vector<unsigned char> toBytes(const std::vector<float>& data) {
  std::vector<unsigned char> bytes(data.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    float v = std::isfinite(data[i]) ? std::clamp(data[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
  }
  return bytes;
}

}  // namespace

void writeImage(const Image& img, const std::string& path) { writeImage(img, path, {}); }

void writeImage(const Image& img, const std::string& path, const ImageNumbers& numbers, ExrCompression compression) {
  throwIfInterrupted();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error("cannot create image writer for " + path + ": " + OIIO::geterror());
  const bool isExr = isFileKind(path, FileKind::Exr);
  OIIO::ImageSpec spec(img.width, img.height, img.numChannels(),
                       isExr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.channelnames = img.channels;
  int a = img.channelIndex("A");
  spec.alpha_channel = a;
  if (isExr) spec.attribute("compression", compression == ExrCompression::Zip ? "zip" : "none");
  if (isFileKind(path, FileKind::Png)) {
    // zlib level 3 without row filters (libpng's PNG_FILTER_NONE, 0x08): 1.5-3 x faster than
    // libpng's default (level 6, adaptive filters) on inim's images, within -7 % (contact sheet,
    // plots) to +17 % (smooth views) of the size.
    spec.attribute("png:compressionLevel", 3);
    spec.attribute("png:filter", 0x08);
  }
  for (const auto& [name, value] : numbers)
    if (isExr) spec.attribute(name, OIIO::TypeDesc::DOUBLE, &value);
  // OIIO stamps EXRs with the time of writing unless DateTime is set; empty writes none, so
  // identical runs give identical bytes.
  spec.attribute("DateTime", "");
  if (!out->open(path, spec)) throw std::runtime_error("cannot open " + path + ": " + out->geterror());
  bool ok;
  try {
    if (isExr) {
      ok = writeRowBands(*out, img.width, img.height, img.numChannels(), OIIO::TypeDesc::FLOAT, img.data.data());
    } else {
      const std::vector<unsigned char> bytes = toBytes(img.data);
      ok = writeRowBands(*out, img.width, img.height, img.numChannels(), OIIO::TypeDesc::UINT8, bytes.data());
    }
  } catch (...) {
    // A write stopped between bands (Ctrl-C): the writer closes the unfinished file as it goes,
    // and libpng prints "libpng error: ..." about the rows never given; the caller's message
    // (or exit status) is the one that counts, and its OutputSet removes the partial file.
    LibraryStderrSilenced quiet(path);
    out.reset();
    throw;
  }
  if (!ok || !out->close()) throw std::runtime_error("cannot write " + path + ": " + out->geterror());
}

std::optional<double> readImageNumber(const std::string& path, const std::string& name) {
  LibraryStderrSilenced quiet(path);
  checkInputFile(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, "", "", "a readable image (" + oneLine(OIIO::geterror()) + ")");
  const OIIO::ParamValue* p = in->spec().find_attribute(name);
  if (!p) return std::nullopt;
  if (p->type() == OIIO::TypeDesc::DOUBLE) return *static_cast<const double*>(p->data());
  if (p->type() == OIIO::TypeDesc::FLOAT) return double(*static_cast<const float*>(p->data()));
  return std::nullopt;
}

Image readImage(const std::string& path, bool rejectNonFinite) {
  LibraryStderrSilenced quiet(path);
  checkInputFile(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, "", "", "a readable image (" + oneLine(OIIO::geterror()) + ")");
  const OIIO::ImageSpec& spec = in->spec();
  // The size its header declares, before it is allocated.
  checkAllocation(path, "size",
                  std::to_string(spec.width) + " x " + std::to_string(spec.height) + " px x " +
                      std::to_string(spec.nchannels) + " channels",
                  {{double(spec.width) * spec.height * spec.nchannels, sizeof(float)}}, "the image");
  Image img(spec.width, spec.height, spec.channelnames);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.data.data()))
    throw InputError(path, "", "", "a readable image (" + oneLine(in->geterror()) + ")");
  in->close();
  if (rejectNonFinite) {
    for (size_t i = 0; i < img.data.size(); ++i)
      if (!std::isfinite(img.data[i])) {
        size_t px = i / img.channels.size();
        throw InputError(path, "pixel (" + std::to_string(px % img.width) + ", " +
                                   std::to_string(px / img.width) + ") channel " +
                                   img.channels[i % img.channels.size()],
                         std::isnan(img.data[i]) ? "NaN" : "Inf", "finite values");
      }
  }
  return img;
}

}  // namespace inim
