#pragma once
// Reflectance textures for diffuse materials: a constant spectrum, an RGB image (each texel
// turned into a Jakob-Hanika sigmoid reflectance at load), or a procedural printed pattern
// (checker, ruler, slanted edge, Siemens star, a composite scale target) that blends two
// spectra, "background" (paper) and "ink". Procedural patterns are defined in millimetres
// on the surface's local coordinates (st), so a printed target has true physical size
// whatever its uv parameterisation.
#include <string>
#include <vector>

#include "core/geometry.h"
#include "spectral/baked_spectrum.h"
#include "spectral/rgb_to_spectrum.h"

namespace inim {

struct Image;

// Where a ray hit a surface, in texture terms.
struct SurfaceCoords {
  Vec2 uv{0.0f};  // [0,1]^2 parameterisation (images)
  Vec2 st{0.0f};  // local surface coordinates in mm, before the object's scale (patterns)
};

enum class TextureType { Constant, Image, Checker, Ruler, SlantedEdge, SiemensStar, ScaleTarget };

struct PatternParams {
  Vec2 center_mm{0.0f};   // pattern origin in st
  float period_mm = 5.0f;   // checker square size
  float tick_mm = 1.0f;     // ruler tick spacing
  float line_mm = 0.25f;    // ruler/frame line width
  float angle_deg = 5.0f;   // slanted edge tilt from vertical (clockwise)
  int spokes = 36;          // Siemens star: number of dark sectors
  float radius_mm = 10.0f;  // Siemens star radius
  Vec2 size_mm{100.0f, 40.0f};  // scale target: printed area
};

class ReflectanceTexture {
 public:
  ReflectanceTexture() = default;
  static ReflectanceTexture constant(BakedSpectrum s);
  static ReflectanceTexture pattern(TextureType type, BakedSpectrum background, BakedSpectrum ink,
                                    const PatternParams& p);
  // `linearRGB`: an image already in linear Rec.709; texels are clamped to [0,1].
  static ReflectanceTexture image(const Image& linearRGB, bool repeat);

  TextureType type() const { return type_; }
  // The spectrum of a Constant texture (the background of patterns).
  const BakedSpectrum& constantSpectrum() const { return a_; }
  SampledSpectrum evaluate(const SurfaceCoords& c, const SampledWavelengths& lambda) const;
  // Fraction of ink at st, in [0,1] (0 for constants and images).
  float inkFraction(Vec2 st) const;
  // Mean reflectance (over wavelength and, roughly, area); used for light-path heuristics.
  float averageAlbedo() const;
  float maxAlbedo() const;

 private:
  TextureType type_ = TextureType::Constant;
  BakedSpectrum a_, b_;  // background, ink (a_ alone for constants)
  PatternParams p_;
  int w_ = 0, h_ = 0;
  bool repeat_ = false;
  std::vector<SigmoidPolynomial> texels_;
  float imageMean_ = 0.0f, imageMax_ = 0.0f;
};

// Convenience: sRGB transfer function (encoded -> linear).
float srgbToLinear(float v);

}  // namespace inim
