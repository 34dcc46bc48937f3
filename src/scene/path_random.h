#pragma once
// The random numbers of one query ray's path (scene/integrator.h).
//
// Light sampling is the direct integrator's largest noise source: which light a sample takes
// (lights of different colours: a warm key, a cool fill, the environment) and where on an area
// light. So the path's first light sample takes its choice and its point from an Owen-scrambled
// Sobol point indexed by the ray's stratum (FieldRay::stratumIndex(), by default its sample
// number): the samples of one pixel or display ray (one FieldRay::id) then share the lights in
// proportion and cover each light's area evenly, instead of drawing them independently. These are Sobol dimensions 5-7, after the view
// renderers' 0-4 (pixel jitter, lens, wavelength), each with its own scramble from (seed, id), so
// the estimate stays unbiased and depends on (seed, id, sample) only, never on threads.
// Everything else, and every later light sample of a path, draws from the PCG stream.
//
//   PathRandom rng(seed, ray.id, ray.sample, ray.stratumIndex());
//   LightUniforms q = rng.light();     // stratified over the id's samples
//   float u = rng.uniform();           // independent
#include <cstdint>

#include "core/geometry.h"
#include "core/qmc.h"
#include "core/rng.h"

namespace inim {

// The uniforms of one light sample: the light's choice, the point on it, and a spare.
struct LightUniforms {
  float select = 0.0f;
  Vec2 u{0.0f};
  float u3 = 0.0f;
};

class PathRandom : public Rng {
 public:
  // `stratum`: the index of the ray's point in the id's Sobol set (FieldRay::stratumIndex()).
  PathRandom(uint64_t seed, uint64_t id, uint32_t sample, uint32_t stratum) : Rng(Rng::forSample(seed, id, sample)) {
    Rng scramble = Rng::forSample(seed, id, kLightScrambleStream);
    first_.select = SobolSequence::sample(stratum, 5, scramble.nextU32());
    first_.u.x = SobolSequence::sample(stratum, 6, scramble.nextU32());
    first_.u.y = SobolSequence::sample(stratum, 7, scramble.nextU32());
  }
  // The first call: the stratified point; later calls: independent uniforms.
  LightUniforms light() {
    LightUniforms q;
    if (!firstUsed_) {
      firstUsed_ = true;
      q = first_;
    } else {
      q.select = uniform();
      q.u = Vec2(uniform(), uniform());
    }
    q.u3 = uniform();
    return q;
  }

 private:
  static constexpr uint64_t kLightScrambleStream = 0xFFFFFFFFFFFEull;
  LightUniforms first_;
  bool firstUsed_ = false;
};

}  // namespace inim
