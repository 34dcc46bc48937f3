#pragma once
// Colour-space conversion through OpenColorIO, with the project's own config
// (spectra/ocio/config.ocio; OCIO 2.1 has no built-in configs).
// Colour spaces: lin_rec709 (working space, D65), srgb (encoded display), display_p3,
// acescg, cie_xyz_d65.
#include <memory>
#include <string>

#include "core/geometry.h"
#include "core/image.h"

namespace inim {

class ColorSystem {
 public:
  // The shared instance on the shipped config (or $OCIO if set).
  static const ColorSystem& instance();
  // Converts one linear triple between two colour spaces of the config.
  Vec3 convert(const Vec3& v, const std::string& from, const std::string& to) const;
  // Converts the first three channels of every pixel in place.
  void convertImage(Image& img, const std::string& from, const std::string& to) const;
  // 3x3 matrix taking XYZ (D65) to linear Rec.709; column-major glm.
  static Mat3 xyzToRec709();
  static Mat3 rec709ToXYZ();
  const std::string& configPath() const { return path_; }

 private:
  explicit ColorSystem(std::string path);
  std::string path_;
  std::shared_ptr<const void> config_;
  struct Cache;  // processors by (from, to), behind a mutex
  std::shared_ptr<Cache> cache_;
  std::shared_ptr<const void> cpuProcessor(const std::string& from, const std::string& to) const;
};

// Matrix from linear RGB with the given xy primaries and white to XYZ (white Y = 1).
Mat3 rgbToXYZMatrix(const Vec2& r, const Vec2& g, const Vec2& b, const Vec2& white);

// CIEDE2000 colour difference between two CIELAB colours.
double ciede2000(const Vec3d& lab1, const Vec3d& lab2);
// The sRGB transfer function (IEC 61966-2-1), per channel: encode = linear -> sRGB.
float srgbEncode(float linear);
float srgbDecode(float encoded);
// XYZ -> CIELAB relative to a white point XYZ (default D65, Y = 1).
Vec3d xyzToLab(const Vec3d& xyz, const Vec3d& white = {0.95047, 1.0, 1.08883});

}  // namespace inim
