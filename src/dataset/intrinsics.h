#pragma once
// Pinhole intrinsics with OpenCV radial-tangential distortion (k1 k2 p1 p2), as posed-photo
// datasets store them (transforms.json, COLMAP's OPENCV model, Middlebury K).
//
// Pixel convention (docs/design.md §2.4, and NeRF/Nerfstudio): pixel (i, j) covers [i, i+1) x [j, j+1)
// with its centre at (i + 0.5, j + 0.5); row 0 is the top. cx, cy are in that convention,
// so a centred principal point is (w/2, h/2). Normalised coordinates are OpenCV's:
// x = (u - cx)/fx to the right, y = (v - cy)/fy downward, on the plane at unit depth.
#include <glm/glm.hpp>

namespace inim {

struct Intrinsics {
  int width = 0, height = 0;                // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;    // pixels
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0;    // OpenCV radial (k) and tangential (p) terms

  bool distorted() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0; }
  // The same camera with its image resampled to newWidth x newHeight (e.g. downscaled): the
  // focal lengths and principal point scale per axis; distortion (normalised) is unchanged.
  Intrinsics resized(int newWidth, int newHeight) const;
  // tan of the half field of view, the larger of the horizontal and vertical one.
  double tanHalfFov() const;
};

// Normalised undistorted -> normalised distorted coordinates (OpenCV's model).
glm::dvec2 distortNormalized(const Intrinsics& k, glm::dvec2 xy);
// The inverse, by Newton iteration from the distorted point (converges in a few steps for any
// real lens inside its image); returns the best estimate if it does not converge.
glm::dvec2 undistortNormalized(const Intrinsics& k, glm::dvec2 xyDistorted);

// Pixel <-> normalised undistorted coordinates (the two above plus K).
glm::dvec2 pixelToNormalized(const Intrinsics& k, glm::dvec2 pixel);
glm::dvec2 normalizedToPixel(const Intrinsics& k, glm::dvec2 xy);

}  // namespace inim
