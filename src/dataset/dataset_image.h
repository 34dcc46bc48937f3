#pragma once
// Reading one dataset image: encoded values as stored, alpha composited onto a background in
// premultiplied form, then box-downscaled.
#include <string>

#include <glm/glm.hpp>

#include "core/image.h"

namespace inim {

struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  bool hasAlpha = false;
};

// The size and channels of an image file, without its pixels. Throws InputError if unreadable.
ImageHeader readImageHeader(const std::string& path);

// Reads `path` as float RGB in [0, 1] (the encoded values; 8/16-bit PNG scale to [0, 1]).
// Grey images are expanded to RGB. Alpha, when present, is composited: c*a + bg*(1 - a),
// where c is straight colour (PNG stores straight alpha; EXR stores premultiplied colour,
// which is used as c*a directly). Then the image shrinks by `downscale` (area average over
// downscale x downscale blocks; sizes not divisible by it go through OIIO's resize).
// Non-finite values are an InputError naming the file.
Image readDatasetImage(const std::string& path, const glm::vec3& background, int downscale,
                       bool* hadAlpha = nullptr);

// The downscaled size used by readDatasetImage.
inline int downscaledSize(int n, int downscale) { return std::max(1, (n + downscale / 2) / downscale); }

// Area-average downscale of an image by an integer factor (OIIO's resize when the size is not
// a multiple of it). Works for any channel count.
Image downscaleImage(const Image& img, int factor);

}  // namespace inim
