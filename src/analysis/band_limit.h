#pragma once
// What an ideal InIm display of a given lenslet pitch can show of a reference view: the
// reference low-passed, per pixel, by the two apertures every ray of such a display averages
// over (docs/error-budget.md, "band-limited reference"). Against it, a reconstruction's error is
// what the display shows wrongly; the rest of its error against the full reference is what no
// display of that pitch could show.
//
//   lenslet     seen from the camera, each lenslet of an ideal (pinhole) MLA shows one colour:
//               the image is held over boxes of the lenslet pitch P at the MLA plane, P / s
//               image pixels wide (s: the camera's footprint of a pixel on the MLA plane, mm);
//   EI pixel    each displayed ray is the average over the cone its EI pixel (pitch d at gap g)
//               spans from the lenslet, |z| d / g wide at depth z, and seen from the camera at
//               distance D this is |z| d / g x D / (D - z) at the MLA plane's scale.
// The filter is a Gaussian of the same variance as the two boxes together, sigma^2 =
// ((P / s)^2 + (|z| d D / (g (D - z) s))^2) / 12 pixels^2, with z the pixel's own depth (the
// reference's Z; 0 where it sees no surface): a Gaussian because where the lenslet grid falls on
// the image (its phase) is not the reference's to know, and averaging the box over that phase
// leaves a smooth kernel of the same width.
//
//   BandLimit b{lensPitchMm, pixelPitchMm, gapMm, distanceMm, footprintMm};
//   Image limited = bandLimited(refLinear, z, coverage, b);
#include <vector>

#include "core/image.h"

namespace inim {

struct BandLimit {
  double lensPitchMm = 0.0;   // P
  double eiPixelMm = 0.0;     // d, the panel's pixel pitch
  double gapMm = 0.0;         // g, panel to MLA
  double distanceMm = 0.0;    // D, camera to the MLA plane
  double footprintMm = 0.0;   // s, one image pixel on the MLA plane
  // The Gaussian's sigma, in image pixels, at depth z (display frame, mm, > 0 toward the camera).
  double sigmaPx(double zMm) const;
};

// `reference`: linear RGB (other channels are filtered alike); `depthZ`, `coverage`: width x
// height (the reference's Z and A); a pixel with coverage < 0.5 uses z = 0.
Image bandLimited(const Image& reference, const std::vector<float>& depthZ, const std::vector<float>& coverage,
                  const BandLimit& b);

}  // namespace inim
