#pragma once
// A trained 3D Gaussian-splat scene, structure of arrays, with every value already activated
// as the INRIA trainer (graphdeco-inria/gaussian-splatting) activates it: opacity through a
// sigmoid, scale through exp, rotation normalised. Loaders (splats/splat_loaders.h) fill it
// from .ply / compressed .ply / .splat files; SplatField (splats/splat_field.h) renders it.
//
// Frame and units are the file's own: COLMAP/OpenCV axes (x right, y down, z forward),
// unitless. Gaussian i has density opacity[i] * exp(-1/2 |S^-1 R^T (x - position[i])|^2),
// R = rotation of the unit quaternion rotation[i] = (w, x, y, z), S = diag(scale[i]).
//
// Colour: the SH coefficients are the trainer's; its colour is SH(dir) + 0.5, clamped at 0,
// in the space of the training images' encoded (sRGB) pixel values, not linear light.
// SplatField composites in that space, as the trainer's rasteriser does, and linearises the
// result with the sRGB EOTF (declared lin_rec709), as RadianceField does with its NeRF colour.
//
// SH storage: `sh` holds shCount(shDegree) coefficients per splat, each an RGB triple:
//   sh[(i * shCount(shDegree) + k) * 3 + c],  k = 0 the DC term (f_dc_c), k = 1..15 the
//   INRIA f_rest coefficients (f_rest is stored channel-major in files: f_rest_{c*(n-1)+k-1}),
//   c = 0, 1, 2 for red, green, blue.
//
//   Gaussians g = loadGaussians("scene.ply");
//   Vec3 dc = g.shCoeff(0, 0);  // colour = 0.5 + 0.2820948 * dc along any direction
#include <cstddef>
#include <vector>

#include "core/geometry.h"

namespace inim {

// Number of SH coefficients per channel for degree 0..3: 1, 4, 9, 16.
constexpr int splatShCount(int degree) { return (degree + 1) * (degree + 1); }

struct Gaussians {
  std::vector<Vec3> position;
  std::vector<glm::vec4> rotation;  // unit quaternion, (w, x, y, z) in .x .y .z .w
  std::vector<Vec3> scale;          // standard deviations along the rotated axes, > 0
  std::vector<float> opacity;       // in [0, 1]
  int shDegree = 0;                 // 0..3, the same for every splat
  std::vector<float> sh;            // see the storage order above

  size_t size() const { return position.size(); }
  int shPerSplat() const { return splatShCount(shDegree); }
  Vec3 shCoeff(size_t i, int k) const {
    const float* p = &sh[(i * shPerSplat() + k) * 3];
    return Vec3(p[0], p[1], p[2]);
  }
  // Resizes every array for n splats of SH degree `degree` (coefficients zeroed).
  void resize(size_t n, int degree);
};

// Rotation matrix of a unit quaternion (w, x, y, z) as the INRIA trainer builds it: the
// columns are the Gaussian's axes in the world.
glm::mat3 quaternionToMatrix(const glm::vec4& wxyz);

// The SH constant of degree 0 (colour = 0.5 + kShC0 * f_dc).
constexpr float kShC0 = 0.28209479177387814f;

}  // namespace inim
