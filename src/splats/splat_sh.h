#pragma once
// Real spherical harmonics up to degree 3 as the INRIA Gaussian-splatting code evaluates them
// (utils/sh_utils.py and its rasteriser's computeColorFromSH): the same constants and signs,
// so trained coefficients give the trainer's colours. Degree 0..2 agree with
// radiance/spherical_harmonics.h (Plenoxels uses the same basis); degree 3 is added here.
//
//   Vec3 c = splatShColour(g.shDegree, &g.sh[i * g.shPerSplat() * 3], dir);  // SH + 0.5, >= 0
#include <algorithm>

#include "core/geometry.h"

namespace inim {

// The basis functions of degree 0..`degree` at unit direction d, into out[0..(degree+1)^2).
inline void splatShBasis(int degree, const Vec3& d, float* out) {
  out[0] = 0.28209479177387814f;
  if (degree < 1) return;
  const float x = d.x, y = d.y, z = d.z;
  constexpr float C1 = 0.4886025119029199f;
  out[1] = -C1 * y;
  out[2] = C1 * z;
  out[3] = -C1 * x;
  if (degree < 2) return;
  const float xx = x * x, yy = y * y, zz = z * z;
  out[4] = 1.0925484305920792f * x * y;
  out[5] = -1.0925484305920792f * y * z;
  out[6] = 0.31539156525252005f * (2.0f * zz - xx - yy);
  out[7] = -1.0925484305920792f * x * z;
  out[8] = 0.5462742152960396f * (xx - yy);
  if (degree < 3) return;
  out[9] = -0.5900435899266435f * y * (3.0f * xx - yy);
  out[10] = 2.890611442640554f * x * y * z;
  out[11] = -0.4570457994644658f * y * (4.0f * zz - xx - yy);
  out[12] = 0.3731763325901154f * z * (2.0f * zz - 3.0f * xx - 3.0f * yy);
  out[13] = -0.4570457994644658f * x * (4.0f * zz - xx - yy);
  out[14] = 1.445305721320277f * z * (xx - yy);
  out[15] = -0.5900435899266435f * x * (xx - 3.0f * yy);
}

// The trainer's colour along unit direction d: sum_k basis_k(d) coeffs[k] + 0.5, clamped at 0.
// `coeffs` holds (degree+1)^2 RGB triples (Gaussians' storage order).
inline Vec3 splatShColour(int degree, const float* coeffs, const Vec3& d) {
  float basis[16];
  splatShBasis(degree, d, basis);
  Vec3 c(0.5f);
  const int n = (degree + 1) * (degree + 1);
  for (int k = 0; k < n; ++k) c += basis[k] * Vec3(coeffs[3 * k], coeffs[3 * k + 1], coeffs[3 * k + 2]);
  return glm::max(c, Vec3(0.0f));
}

}  // namespace inim
