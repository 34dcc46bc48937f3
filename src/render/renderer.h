#pragma once
// Renders any Field through a camera into a linear Rec.709 image, spectrally: each sample
// carries 4 wavelengths drawn from the visible pdf, and the estimate is accumulated in XYZ.
// RGB-only fields are accumulated in their own colour space and converted through OCIO.
#include <cstdint>
#include <string>

#include "core/image.h"
#include "field/field.h"
#include "render/camera.h"

namespace inim {

struct RenderSettings {
  int spp = 16;
  uint64_t seed = 1;
  bool progress = true;       // a bar on a terminal only
  int raysPerBatch = 4096;    // rays per Field::query call
};

struct RenderResult {
  // Channels R,G,B (linear Rec.709), A (opacity), Z (mean depth in mm of the samples that hit
  // something; 0 where none did, which A = 0 marks).
  Image image;
  double seconds = 0;
  uint64_t raysTraced = 0;
};

RenderResult renderField(const Field& field, const ThinLensCamera& camera, const RenderSettings& s);

// Encodes the RGB channels of a linear Rec.709 image to sRGB (through OCIO) and returns an
// RGB image ready for PNG.
Image encodeSRGB(const Image& linearRec709);

}  // namespace inim
