#pragma once
// Real spherical harmonics up to degree 2, the view-dependent colour basis of Plenoxels.
// Constants and sign conventions follow Plenoxels/svox2 so coefficients are comparable.
#include "core/geometry.h"

namespace inim {

// Number of basis functions for degree 0..2: 1, 4, 9.
constexpr int shCount(int degree) { return (degree + 1) * (degree + 1); }
constexpr int kMaxShCount = 9;

// Evaluates the first shCount(degree) basis functions at unit direction d into out[].
inline void evalSh(int degree, const Vec3& d, float* out) {
  out[0] = 0.28209479177387814f;
  if (degree < 1) return;
  out[1] = -0.4886025119029199f * d.y;
  out[2] = 0.4886025119029199f * d.z;
  out[3] = -0.4886025119029199f * d.x;
  if (degree < 2) return;
  float xx = d.x * d.x, yy = d.y * d.y, zz = d.z * d.z;
  out[4] = 1.0925484305920792f * d.x * d.y;
  out[5] = -1.0925484305920792f * d.y * d.z;
  out[6] = 0.31539156525252005f * (2.0f * zz - xx - yy);
  out[7] = -1.0925484305920792f * d.x * d.z;
  out[8] = 0.5462742152960396f * (xx - yy);
}

}  // namespace inim
