#pragma once
// From linear camera RGB to what `inim view` / `inim reference` write: the exposure (fixed or
// automatic) and the sRGB encoding through the sensor's fitted camera RGB -> XYZ matrix and
// OCIO (cie_xyz_d65 -> srgb).
#include <string>

#include "camera/sensor.h"
#include "core/image.h"

namespace inim {

struct Exposure {
  bool automatic = true;
  double factor = 1.0;       // fixed factor when not automatic
  double percentile = 99.0;  // automatic: this percentile of the brightest linear Rec.709
  double target = 0.9;       //   channel over the pixels with signal maps to `target`
};

// Parses "auto" or a number > 0 (InputError naming `key` otherwise).
Exposure parseExposure(const std::string& text, const std::string& key = "--exposure");

// The factor: fixed, or target / (the percentile of max(R, G, B) in linear Rec.709 over the
// blocks of b x b pixels that have signal, b = max(1, round(width / 200)), each block averaged
// first, so that Monte Carlo noise (single bright samples) does not set the exposure).
// 1 when no pixel has signal.
double exposureFactor(const Image& cameraRgb, const CameraSensor& sensor, const Exposure& e);

// Multiplies the first three channels by k (a copy).
Image scaledImage(const Image& img, double k);

// Camera RGB (already exposed) -> XYZ (sensor.toXyz) -> sRGB (OCIO cie_xyz_d65 -> srgb),
// clamped to [0, 1]: an RGB image ready for an 8-bit PNG.
Image cameraRgbToSrgb(const Image& cameraRgb, const CameraSensor& sensor);

}  // namespace inim
