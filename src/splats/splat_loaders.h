#pragma once
// Gaussian-splat files -> Gaussians (splats/gaussians.h), activated as the INRIA trainer does.
//
//  - INRIA PLY (the trainer's point_cloud.ply, and Polycam, Luma, Nerfstudio splatfacto exports):
//    binary little-endian (or ascii) element `vertex` with properties found BY NAME: x y z, optional
//    nx ny nz, f_dc_0..2, f_rest_0..(0|9|24|45) (SH degree 0..3, channel-major), opacity
//    (sigmoid), scale_0..2 (exp), rot_0..3 (w first, normalised); any scalar type (float,
//    double, uchar, ...); other properties, comments and bytes after the last element ignored.
//  - SuperSplat/PlayCanvas compressed PLY: element `chunk` (per 256 splats: min/max position,
//    log-scale and optionally colour), element `vertex` of 4 uint32 (packed_position 11/10/11
//    bits, packed_rotation = index of the largest component (w-first) in 2 bits + the other three
//    in 3 x 10 bits scaled by 1/sqrt(2), packed_scale 11/10/11, packed_color RGBA 8888 with
//    A = sigmoid(opacity)), optional element `sh` of uchar f_rest_* (value = byte * 8/255 - 4).
//    As decoded by playcanvas/engine src/scene/gsplat/gsplat-compressed-data.js.
//  - .splat (antimatter15/splat): 32 bytes per splat, position float32 x 3, scale float32 x 3
//    (already exp), RGBA uint8 = 255 (0.5 + C0 f_dc), 255 sigmoid(opacity), quaternion uint8 x 4
//    = 128 (w, x, y, z) + 128. SH degree 0.
//
// Bad input is an InputError(file, "element.property", value, expected): an unsupported format
// (big-endian, unknown), a malformed ascii number, truncated data or a row count the file
// cannot hold (checked before allocating), a missing property, NaN/Inf, a zero-length
// quaternion, a log-scale whose exp overflows, no splats.
//
//   Gaussians g = loadGaussians("scenes/splats/guitar.compressed.ply");
#include <string>

#include "splats/gaussians.h"

namespace inim {

class PlyFile;

// By extension (.ply: INRIA or compressed, told by the header; .splat).
Gaussians loadGaussians(const std::string& path);

Gaussians loadInriaPly(const PlyFile& ply);
Gaussians loadCompressedPly(const PlyFile& ply);
Gaussians loadSplatFile(const std::string& path);

// Largest |log scale| accepted: exp(80) and exp(-80) are finite and nonzero in float.
constexpr float kMaxAbsLogScale = 80.0f;

}  // namespace inim
