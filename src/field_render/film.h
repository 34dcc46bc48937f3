#pragma once
// What turns the field's answers along a pixel's camera rays into the pixel's values: the part
// of the field renderer (field_render/field_renderer.h) that differs between products, e.g. linear
// Rec.709 with opacity and depth for `inim render`, camera RGB through a sensor's spectral
// response for the reference view.
#include <span>
#include <string>
#include <vector>

#include "field/field.h"

namespace inim {

// The camera rays of one pixel after the field answered them, in sample order (a vignetted
// sample has no ray).
struct PixelRays {
  std::span<const FieldSample> answers;
  std::span<const FieldRay> rays;                   // the rays answered, in the field's frame
  std::span<const SampledWavelengths> wavelengths;  // one per ray for a spectral field, else empty
  std::span<const float> weights;                   // the camera's weight / rays per sample
  int spp = 1;                                      // camera samples of the pixel
  bool spectral = true;                             // the field answers L at the wavelengths
  // A dispersive camera traced one ray per wavelength of a sample: each ray stands for its hero
  // wavelength (index 0) only. A packet the field terminated carries 4x the hero in L[0].
  bool heroOnly = false;
};

class Film {
 public:
  virtual ~Film() = default;
  virtual std::vector<std::string> channels() const = 0;
  // Writes channels().size() values of one pixel. Called from many threads at once.
  virtual void resolvePixel(const PixelRays& rays, float* pixel) const = 0;
};

}  // namespace inim
