#include "display_view/estimators/sample_tracer.h"

namespace inim {

namespace {

constexpr uint64_t kScrambleStream = 0xFFFFFFFFFFFFull;  // sample slot of the Sobol scramble seeds
constexpr uint64_t kMlaSalt = 0x5EED0F3A11A0ull;         // salts the per-sample MLA stream

}  // namespace

SampleTracer::SampleTracer(const EstimatorContext& context, RayCounts& counts) : context_(context), counts_(counts) {}

void SampleTracer::beginPixel(int x, int y) {
  x_ = x;
  y_ = y;
  pixelIndex_ = uint64_t(y) * uint64_t(context_.camera.width()) + uint64_t(x);
  Rng scrambleRng = Rng::forSample(context_.settings.seed, pixelIndex_, kScrambleStream);
  for (auto& v : scramble_) v = scrambleRng.nextU32();
}

SampleTracer::Outcome SampleTracer::trace(const Ray& ray, float lambda, Rng& rng, const PanelRead& read,
                                          std::array<float, kNumPrimaries>& emission, float& throughput) {
  ++counts_.traced;
  const float frontZ = context_.frontZ;
  if (!(ray.d.z < 0.0f) || !(ray.o.z > frontZ)) return Outcome::Background;
  const float t = (frontZ - ray.o.z) / ray.d.z;
  const Point3 p = ray.o + t * ray.d;
  if (!context_.area.contains(p.x, p.y)) return Outcome::Background;
  ++counts_.onDisplay;
  PanelArrival arrival;
  if (!context_.mla.traceToPanel(Ray{p, ray.d, 0.0f, kInfinity}, lambda, rng, arrival)) return Outcome::Nothing;
  ++counts_.onPanel;
  throughput = arrival.throughput;
  emission = {0.0f, 0.0f, 0.0f};
  const PanelEmitter& panel = context_.panel;
  if (!read.box) {
    const PanelEmission e = panel.emit(arrival, lambda);
    if (e.channel < 0 || e.weight == 0.0f) return Outcome::Nothing;
    emission[size_t(e.channel)] = e.weight;
  } else {
    Vec2d uv;
    float factor = 0.0f;
    if (!panel.emissionPointPx(arrival.p, arrival.d, lambda, uv, factor)) return Outcome::Nothing;
    emission = panel.boxAveragePx(uv.x - read.halfU, uv.y - read.halfV, uv.x + read.halfU, uv.y + read.halfV);
    for (auto& v : emission) v *= factor;
    if (emission[0] == 0.0f && emission[1] == 0.0f && emission[2] == 0.0f) return Outcome::Nothing;
  }
  ++counts_.emitting;
  return Outcome::Panel;
}

void SampleTracer::addSample(int index, const PanelRead& read, Vec3d& rgb) {
  const CameraModel& camera = context_.camera;
  const ChannelResponse& channels = context_.channels;
  const double background = context_.settings.backgroundY;
  const float lambdaRef = context_.referenceLambdaNm;
  const uint32_t idx = uint32_t(index);
  const Vec2 pix(float(x_) + SobolSequence::sample(idx, 0, scramble_[0]),
                 float(y_) + SobolSequence::sample(idx, 1, scramble_[1]));
  const Vec2 lens(SobolSequence::sample(idx, 2, scramble_[2]), SobolSequence::sample(idx, 3, scramble_[3]));
  const float uLambda = SobolSequence::sample(idx, 4, scramble_[4]);
  Rng rng = Rng::forSample(context_.settings.seed ^ kMlaSalt, pixelIndex_, uint64_t(index));
  std::array<float, kNumPrimaries> emission{};
  float throughput = 1.0f;
  Ray ray;
  if (!channels.dispersive()) {
    const float w = camera.generateRay(pix, lens, lambdaRef, ray);
    if (!(w > 0.0f)) return;
    const Outcome o = trace(ray, lambdaRef, rng, read, emission, throughput);
    if (o == Outcome::Background) {
      rgb += double(w) * background;
    } else if (o == Outcome::Panel) {
      channels.add(emission, double(w) * throughput, lambdaRef, 1.0f, -1, uLambda, rgb);
    }
    return;
  }

  // Dispersive: one ray per slot (primary, or wavelength of the packet); the camera ray is
  // shared by the slots when the camera itself is not dispersive.
  const int slots = channels.raysPerSample();
  float sharedWeight = 0.0f;
  Ray shared;
  const bool shareRay = !context_.cameraDispersive;
  if (shareRay) {
    sharedWeight = camera.generateRay(pix, lens, lambdaRef, shared);
    if (!(sharedWeight > 0.0f)) return;
  }
  SampledWavelengths packet;
  if (!channels.primaries()) packet = SampledWavelengths::sampleVisible(uLambda);
  for (int slot = 0; slot < slots; ++slot) {
    float lambda, pdf;
    if (!channels.slotWavelength(slot, uLambda, packet, lambda, pdf)) continue;
    float w = sharedWeight;
    if (!shareRay) {
      w = camera.generateRay(pix, lens, lambda, ray);
      if (!(w > 0.0f)) continue;
    } else {
      ray = shared;
    }
    const Outcome o = trace(ray, lambda, rng, read, emission, throughput);
    if (o == Outcome::Background) {
      rgb += double(w) * background / double(slots);
    } else if (o == Outcome::Panel) {
      channels.add(emission, double(w) * throughput, lambda, pdf, slot, uLambda, rgb);
    }
  }
}

}  // namespace inim
