#pragma once
// The Field interface: anything that returns radiance along rays. Every later stage
// (EIA synthesis, reference views) works with any Field: an analytic Embree scene, a
// trained radiance field, or colours filled in by an external renderer.
//
// Queries come in batches so that fields can vectorise (a grid NeRF marches many rays at
// once; an external field looks rays up by index). A field is either spectral (it answers
// at the sample's 4 wavelengths) or RGB-only (it answers linear RGB in a declared colour
// space); callers ask `encoding()` and convert, they never guess.
#include <cstdint>
#include <span>
#include <string>

#include "core/geometry.h"
#include "spectral/sampled.h"

namespace inim {

struct FieldRay {
  Point3 o;            // origin, field/display frame, mm
  Vec3 d;              // unit direction into the scene
  float tNear = 0.0f;  // query interval along d (the VCP is the near plane)
  float tFar = kInfinity;
  uint64_t id = 0;      // stable index (pixel or display ray) that keys the random stream
  uint32_t sample = 0;  // sample number within that id
  // The point of the id's stratified sample set this ray uses (scene/path_random.h): rays that
  // stand for one sample (a dispersive camera's wavelengths) share it. kSameAsSample: `sample`.
  static constexpr uint32_t kSameAsSample = 0xFFFFFFFFu;
  uint32_t stratum = kSameAsSample;
  uint32_t stratumIndex() const { return stratum == kSameAsSample ? sample : stratum; }
};

struct FieldSample {
  SampledSpectrum L;     // spectral radiance at the wavelengths (spectral fields)
  Vec3 rgb{0.0f};        // linear RGB radiance (RGB fields)
  float depth = kInfinity;  // distance along the ray to the first surface (or expected depth)
  float opacity = 0.0f;     // 1 for a hit on an opaque surface, accumulated alpha for volumes
  // A dispersive event kept only the hero wavelength: L[0] then carries 4x the hero radiance
  // and L[1..3] are 0 (pbrt-v4's estimator expressed with the caller's unchanged pdfs). A
  // consumer that uses only the hero wavelength divides L[0] by 4 when this is set.
  bool secondaryTerminated = false;
};

enum class FieldEncoding { Spectral, RGB };

class Field {
 public:
  virtual ~Field() = default;
  virtual FieldEncoding encoding() const = 0;
  // The colour space of RGB answers (an OCIO colour-space name from the shipped config).
  virtual std::string colorSpace() const { return "lin_rec709"; }
  // Answers out[i] for rays[i]. `lambda[i]` is used by spectral fields only (RGB fields may
  // be passed an empty span). `seed` is the run's seed; randomness comes from
  // (seed, ray.id, ray.sample) only, so any batch split gives the same answers.
  virtual void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
                     std::span<FieldSample> out, uint64_t seed) const = 0;
  // The same answers, approximated where the field has a cost-for-accuracy knob, for previews
  // that must keep up with the user (the placement page's level 0); by default the full query.
  virtual void queryPreview(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
                            std::span<FieldSample> out, uint64_t seed) const {
    query(rays, lambda, out, seed);
  }
  // Axis-aligned bounds of the content, in the field frame (for placement and previews);
  // lo > hi when unknown (colours answered by an external renderer).
  virtual void bounds(Point3& lo, Point3& hi) const = 0;
  // False when answers carry no depth (FieldSample::depth stays infinite even on a hit): the
  // synthesis then decides hits by opacity alone and leaves the Z channel empty.
  virtual bool answersDepth() const { return true; }
};

}  // namespace inim
