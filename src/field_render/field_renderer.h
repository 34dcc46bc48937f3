#pragma once
// The one renderer of a Field through a camera (camera/camera_model.h): `inim render`,
// `inim capture` and the reference view all go through it, each with its own pixel sampler
// (field_render/pixel_sampler.h) and film (field_render/film.h).
//
// Per pixel and camera sample: the camera turns the sample into a ray with a weight (no ray
// when the weight is 0), the ray goes to the field's frame, and the field is queried in
// batches. Spectral fields get pbrt-v4's 4-wavelength packet (sampleVisible). A dispersive
// camera bends each wavelength its own way: one camera ray per wavelength of the stratified
// packet, each carrying the packet rotated so that its own wavelength is the hero (index 0),
// weighted 1/4 (unbiased, and as little colour noise as one ray carrying 4 wavelengths);
// otherwise one ray carries the 4 wavelengths.
//
// Ray ids are pixel indices (y * width + x) and ray samples k * spp + sample (k: the packet's
// rotation, 0 when not dispersive), so the field's random streams, and the image, are the same
// for any thread count and batch size. That order gives each rotation (each hero wavelength) an
// aligned block of sample numbers, which fields stratify over (scene/path_random.h): numbers
// interleaved by k would give each hero wavelength a strided, badly stratified subset.
#include <cstdint>
#include <optional>
#include <vector>

#include "camera/camera_model.h"
#include "core/image.h"
#include "core/transform.h"
#include "field/field.h"
#include "field_render/film.h"
#include "field_render/pixel_sampler.h"

namespace inim {

struct FieldRenderSettings {
  int spp = 16;                    // camera samples per pixel, >= 1
  const char* sppKey = "spp";      // the setting spp came from, named when it is refused
  uint64_t seed = 1;               // the field's seed (Field::query)
  int raysPerBatch = 4096;         // rays per Field::query call
  bool progress = true;            // a bar on a terminal only
  const char* progressLabel = "render";
  // From the camera's frame to the field's; none: camera rays go to the field unchanged.
  std::optional<Transform> cameraToField;
  // False: a dispersive camera's rays are traced at 550 nm, each carrying the whole packet (for
  // a lens whose colour spread is far below a pixel: camera/chromatic_spread.h).
  bool traceDispersion = true;
  // Where a comparison reads only some pixels: the others (0 in this width x height map) get
  // sppElsewhere samples, the first of their full set (0: none, the pixel stays 0). A pixel's
  // samples do not depend on the map, so pixels rendered in several passes are the same.
  const std::vector<uint8_t>* fullSamples = nullptr;
  int sppElsewhere = 1;
};

struct FieldRenderStats {
  uint64_t cameraRays = 0;  // rays sent to the field
  uint64_t hitRays = 0;     // of which the field answered with opacity > 0
  int raysPerSample = 1;    // kNumWavelengths with a dispersive camera, else 1
  double seconds = 0.0;
};

struct FieldRender {
  Image image;              // camera.width() x camera.height(), the film's channels
  FieldRenderStats stats;
};

FieldRender renderThroughCamera(const Field& field, const CameraModel& camera, const PixelSampler& sampler,
                                const Film& film, const FieldRenderSettings& settings);

}  // namespace inim
