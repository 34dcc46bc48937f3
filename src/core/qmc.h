#pragma once
// Owen-scrambled Sobol points for per-pixel sample sets (the view renderers' pixel jitter,
// lens position, wavelength): well stratified in every projection, so edges (subpixels, the
// black matrix, lenslet borders) converge faster than with independent random numbers, and
// unbiased, because every pixel's point set gets its own random nested scramble.
//
// The first eight Sobol dimensions (van der Corput, then Joe & Kuo's direction numbers for
// dimensions 2-8): 0-4 for the view renderers' pixel jitter, lens and wavelength, 5-7 for the
// scenes' first light sample (scene/path_random.h). Scramble seeds come from the pixel's Rng::forSample stream, so the points
// depend on (seed, pixel, sample index) only, never on threads.
#include <algorithm>
#include <array>
#include <cstdint>

namespace inim {

class SobolSequence {
 public:
  static constexpr int kDims = 8;
  // The unscrambled 32-bit value of point `index` in dimension `dim` (0..7).
  static uint32_t value(uint32_t index, int dim) {
    const auto& v = table()[size_t(dim)];
    uint32_t x = 0;
    for (int b = 0; index; index >>= 1, ++b)
      if (index & 1u) x ^= v[size_t(b)];
    return x;
  }
  // Owen-scrambled point in [0, 1) (Laine-Karras style hash; pbrt-v4's FastOwenScrambler).
  static float sample(uint32_t index, int dim, uint32_t seed) {
    uint32_t v = reverseBits(value(index, dim));
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    v = reverseBits(v);
    return std::min(float(v >> 8) * 0x1p-24f, 0x1.fffffep-1f);
  }

 private:
  static uint32_t reverseBits(uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
  }
  using Table = std::array<std::array<uint32_t, 32>, kDims>;
  static const Table& table() {
    static const Table t = [] {
      Table r{};
      for (int b = 0; b < 32; ++b) r[0][size_t(b)] = 1u << (31 - b);
      // Joe & Kuo (new-joe-kuo-6.21201), dimensions 2..8: degree s, coefficients a, m_1..m_s.
      const int s[7] = {1, 2, 3, 3, 4, 4, 5};
      const uint32_t a[7] = {0, 1, 1, 2, 1, 4, 2};
      const uint32_t m[7][5] = {{1, 0, 0, 0, 0}, {1, 3, 0, 0, 0}, {1, 3, 1, 0, 0}, {1, 1, 1, 0, 0},
                                {1, 1, 3, 3, 0}, {1, 3, 5, 13, 0}, {1, 1, 5, 5, 17}};
      for (int d = 0; d < 7; ++d) {
        auto& v = r[size_t(d + 1)];
        const int sd = s[d];
        for (int i = 0; i < sd; ++i) v[size_t(i)] = m[d][i] << (31 - i);
        for (int i = sd; i < 32; ++i) {
          uint32_t x = v[size_t(i - sd)] ^ (v[size_t(i - sd)] >> sd);
          for (int k = 1; k < sd; ++k)
            if ((a[d] >> (sd - 1 - k)) & 1u) x ^= v[size_t(i - k)];
          v[size_t(i)] = x;
        }
      }
      return r;
    }();
    return t;
  }
};

}  // namespace inim
