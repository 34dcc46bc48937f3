#include "display_view/reference_renderer.h"

#include <algorithm>
#include <cmath>

#include "camera/chromatic_spread.h"
#include "core/error.h"
#include "core/rng.h"
#include "field_render/field_renderer.h"
#include "spectral/color.h"
#include "core/qmc.h"
#include "display_view/aperture_mean.h"
#include "display_view/reference_cache.h"

namespace inim {

const char* cameraDispersionName(CameraDispersion d) {
  return d == CameraDispersion::Trace ? "trace" : d == CameraDispersion::Ignore ? "ignore" : "auto";
}

namespace {

constexpr uint64_t kScrambleStream = 0xFFFFFFFFFFFFull;

// Owen-scrambled Sobol points, a scramble per pixel from its own Rng stream (core/qmc.h).
class ScrambledSobolSampler final : public PixelSampler {
 public:
  explicit ScrambledSobolSampler(uint64_t seed) : seed_(seed) {}
  void pixelSamples(uint64_t pixelIndex, std::span<CameraSample> out) const override {
    Rng scramble = Rng::forSample(seed_, pixelIndex, kScrambleStream);
    uint32_t sc[SobolSequence::kDims];
    for (auto& v : sc) v = scramble.nextU32();
    for (size_t i = 0; i < out.size(); ++i) {
      const uint32_t idx = uint32_t(i);
      out[i].pixelOffset = Vec2(SobolSequence::sample(idx, 0, sc[0]), SobolSequence::sample(idx, 1, sc[1]));
      out[i].lens = Vec2(SobolSequence::sample(idx, 2, sc[2]), SobolSequence::sample(idx, 3, sc[3]));
      // The packet spreads its 4 wavelengths by quarters from this (field_render/field_renderer.h), so
      // only its value within [0, 1/4) matters: there the pixel's 4 x spp wavelengths are
      // stratified at 1 / (4 spp), where points spread over [0, 1) would leave 4 spp strata only.
      out[i].wavelength = 0.25f * SobolSequence::sample(idx, 4, sc[4]);
    }
  }

 private:
  uint64_t seed_;
};

// Linear white-balanced camera RGB, accumulated in double: the surviving rays averaged by their
// weights, times the pixel's mean camera weight (display_view/aperture_mean.h).
class CameraRgbFilm final : public Film {
 public:
  // `rgbToCamera`: an RGB field's colours to camera RGB (unused for spectral fields).
  CameraRgbFilm(const CameraSensor& sensor, const glm::dmat3& rgbToCamera, const ApertureMeanWeight& meanWeight,
                int width)
      : sensor_(sensor), rgbToCamera_(rgbToCamera), meanWeight_(meanWeight), width_(uint64_t(width)) {}
  std::vector<std::string> channels() const override { return {"R", "G", "B"}; }

  void resolvePixel(const PixelRays& p, float* pixel) const override {
    Vec3d acc(0.0);
    double weights = 0.0;
    for (size_t i = 0; i < p.answers.size(); ++i) {
      weights += double(p.weights[i]);
      const Vec3d c = p.spectral ? spectralRgb(p.answers[i], p.wavelengths[i], p.heroOnly)
                                 : rgbToCamera_ * Vec3d(p.answers[i].rgb);
      if (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) acc += double(p.weights[i]) * c;
    }
    const double scale = weights > 0.0 ? meanWeightOf(p.rays.front().id) / weights : 0.0;
    for (int c = 0; c < 3; ++c) pixel[c] = float(acc[c] * scale);
  }

 private:
  Vec3d spectralRgb(const FieldSample& f, const SampledWavelengths& wl, bool heroOnly) const {
    Vec3d c(0.0);
    if (heroOnly) {
      // This ray's own (hero) wavelength only; a terminated packet carries 4x the hero.
      const float pdf = wl.pdf()[0];
      const double L0 = double(f.L[0]) / (f.secondaryTerminated ? double(kNumWavelengths) : 1.0);
      if (pdf > 0.0f && std::isfinite(L0)) c = sensor_.response(wl[0]) * (L0 / pdf);
      return c;
    }
    for (int k = 0; k < kNumWavelengths; ++k) {
      const float pdf = wl.pdf()[k];
      if (!(pdf > 0.0f) || !std::isfinite(f.L[k])) continue;
      c += sensor_.response(wl[k]) * (double(f.L[k]) / pdf);
    }
    return c / double(kNumWavelengths);
  }

  // Ray ids are pixel indices, y * width + x (field_render/field_renderer.h).
  double meanWeightOf(uint64_t pixel) const {
    return meanWeight_.at(Vec2(float(pixel % width_) + 0.5f, float(pixel / width_) + 0.5f));
  }

  const CameraSensor& sensor_;
  glm::dmat3 rgbToCamera_;
  const ApertureMeanWeight& meanWeight_;
  uint64_t width_;
};

// Another film's channels, then A (the fraction of the rays that hit), Z (the mean display z of
// the hits) and dZ (their max - min): the hit is found in the field frame, where
// FieldSample::depth is measured.
class WithSurfaceDepth final : public Film {
 public:
  WithSurfaceDepth(const Film& colour, const Transform& fieldToDisplay)
      : colour_(colour), fieldToDisplay_(fieldToDisplay), colourChannels_(colour.channels().size()) {}
  std::vector<std::string> channels() const override {
    std::vector<std::string> c = colour_.channels();
    c.push_back("A");
    c.push_back("Z");
    c.push_back("dZ");
    return c;
  }

  void resolvePixel(const PixelRays& p, float* pixel) const override {
    colour_.resolvePixel(p, pixel);
    size_t hits = 0, depths = 0;
    double zSum = 0.0, zMin = 0.0, zMax = 0.0;
    for (size_t i = 0; i < p.answers.size(); ++i) {
      const FieldSample& f = p.answers[i];
      if (!(f.opacity > 0.0f)) continue;
      ++hits;
      if (!std::isfinite(f.depth)) continue;
      const FieldRay& r = p.rays[i];
      const Point3d hit = Point3d(r.o) + double(f.depth) * Vec3d(r.d);
      const double z = fieldToDisplay_.point(hit).z;
      zMin = depths ? std::min(zMin, z) : z, zMax = depths ? std::max(zMax, z) : z;
      zSum += z;
      ++depths;
    }
    const size_t rays = p.answers.size();
    pixel[colourChannels_] = rays ? float(double(hits) / double(rays)) : 0.0f;
    pixel[colourChannels_ + 1] = depths ? float(zSum / double(depths)) : 0.0f;
    pixel[colourChannels_ + 2] = float(zMax - zMin);
  }

 private:
  const Film& colour_;
  const Transform& fieldToDisplay_;
  size_t colourChannels_;
};

// An RGB field's colour space -> XYZ (linear: the matrix of the basis vectors) -> camera RGB.
glm::dmat3 rgbToCameraMatrix(const Field& field, const CameraSensor& sensor) {
  glm::dmat3 toXyz;
  const auto& cs = ColorSystem::instance();
  for (int i = 0; i < 3; ++i) {
    Vec3 e(0.0f);
    e[i] = 1.0f;
    toXyz[i] = Vec3d(cs.convert(e, field.colorSpace(), "cie_xyz_d65"));
  }
  return sensor.xyzToCameraRgb() * toXyz;
}

}  // namespace

ViewResult renderReference(const Field& field, const Transform& fieldToDisplay, const CameraModel& camera,
                           const CameraSensor& sensor, const ReferenceSettings& s) {
  if (s.spp < 1) throw InputError("", s.sppKey, std::to_string(s.spp), "a whole number >= 1");
  const std::string cacheDir = s.fieldKey.empty() ? "" : !s.cacheDir.empty() ? s.cacheDir : referenceCacheDir();
  const std::string key = cacheDir.empty() ? "" : referenceCacheKey(s.fieldKey, fieldToDisplay, camera, sensor, s);
  ReferenceClaim claim;  // held while this run renders the entry: concurrent runs wait for it
  if (!key.empty())
    if (std::optional<ViewResult> cached = loadOrClaimReference(cacheDir, key, claim)) {
      cached->cached = true;
      return std::move(*cached);
    }
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  const ApertureMeanWeight meanWeight(camera);
  const CameraRgbFilm film(sensor, spectral ? glm::dmat3(1.0) : rgbToCameraMatrix(field, sensor), meanWeight,
                           camera.width());
  FieldRenderSettings fs;
  fs.spp = s.spp;
  fs.sppKey = s.sppKey;
  fs.seed = s.seed;
  fs.raysPerBatch = s.raysPerBatch;
  fs.progress = s.progress;
  fs.progressLabel = "reference";
  fs.fullSamples = s.fullSamples;
  fs.sppElsewhere = s.sppElsewhere;
  fs.cameraToField = fieldToDisplay.inverse();
  fs.traceDispersion = s.dispersion == CameraDispersion::Trace ||
                       (s.dispersion == CameraDispersion::Auto && chromaticSpreadPx(camera) > kDispersionThresholdPx);
  const WithSurfaceDepth filmWithDepth(film, fieldToDisplay);
  const Film& used = s.depth ? static_cast<const Film&>(filmWithDepth) : film;
  FieldRender r = renderThroughCamera(field, camera, ScrambledSobolSampler(s.seed), used, fs);

  ViewResult out;
  out.image = std::move(r.image);
  out.stats.tracedRays = r.stats.cameraRays;
  out.stats.emittingRays = r.stats.hitRays;
  out.stats.raysPerSample = r.stats.raysPerSample;
  out.stats.dispersive = fs.traceDispersion && camera.isDispersive();
  out.stats.seconds = r.stats.seconds;
  if (!key.empty()) storeCachedReference(cacheDir, key, out);
  return out;
}

}  // namespace inim
