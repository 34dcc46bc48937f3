#pragma once
// Which pixels of an image count (for metrics, and for comparing views only where the display
// is seen): one byte per pixel, row-major.
#include <cstdint>
#include <string>
#include <vector>

namespace inim {

struct PixelMask {
  int width = 0, height = 0;
  std::vector<uint8_t> on;  // row-major, 1 = the pixel counts
  std::string source;       // the file (or a description) for messages

  bool counts(int x, int y) const { return on[size_t(y) * width + x] != 0; }
  int64_t count() const {
    int64_t n = 0;
    for (uint8_t v : on) n += v ? 1 : 0;
    return n;
  }
};

}  // namespace inim
