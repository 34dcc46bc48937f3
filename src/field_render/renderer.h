#pragma once
// `inim render` and `inim capture`'s image of any Field through a camera: linear Rec.709 with
// opacity and depth, rendered spectrally by the field renderer (field_render/field_renderer.h) with
// independent samples (field_render/pixel_sampler.h). Each sample carries 4 wavelengths drawn from
// the visible pdf and the estimate is accumulated in XYZ; RGB-only fields are accumulated in
// their own colour space and converted through OCIO.
#include <cstdint>
#include <string>

#include "camera/camera_model.h"
#include "core/image.h"
#include "field/field.h"

namespace inim {

struct RenderSettings {
  int spp = 16;               // < 1 counts as 1
  uint64_t seed = 1;
  bool progress = true;       // a bar on a terminal only
  int raysPerBatch = 4096;    // rays per Field::query call
};

struct RenderResult {
  // Channels R,G,B (linear Rec.709), A (opacity), Z (mean depth in mm of the samples that hit
  // something; 0 where none did, which A = 0 marks).
  Image image;
  double seconds = 0;
  uint64_t raysTraced = 0;    // camera rays sent to the field
};

// The camera's weight scales each sample's colour and opacity (FovCameraModel's is 1).
RenderResult renderField(const Field& field, const CameraModel& camera, const RenderSettings& s);

// Encodes the RGB channels of a linear Rec.709 image to sRGB (through OCIO) and returns an
// RGB image ready for PNG.
Image encodeSRGB(const Image& linearRec709);

}  // namespace inim
