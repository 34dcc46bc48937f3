#include "field_render/field_renderer.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"
#include "core/progress.h"
#include "core/error.h"
#include "core/size_budget.h"

namespace inim {

namespace {

constexpr int kTileSize = 16;
// Camera sample points tried per sample kept (see TileRenderer::pixelRays).
constexpr size_t kAttemptsPerSample = 4;

// The camera rays of one tile, pixel after pixel; pixel i owns rays [pixelStart[i], pixelStart[i + 1]).
struct TileRays {
  std::vector<FieldRay> rays;
  std::vector<SampledWavelengths> wavelengths;  // spectral fields only
  std::vector<float> weights;
  std::vector<size_t> pixelStart;
};

class TileRenderer {
 public:
  TileRenderer(const Field& field, const CameraModel& camera, const PixelSampler& sampler, const Film& film,
               const FieldRenderSettings& settings)
      : field_(field), camera_(camera), sampler_(sampler), film_(film), settings_(settings),
        spectral_(field.encoding() == FieldEncoding::Spectral),
        dispersive_(settings.traceDispersion && camera.isDispersive()),
        raysPerSample_(dispersive_ ? kNumWavelengths : 1) {}

  int raysPerSample() const { return raysPerSample_; }

  // Renders the pixels of `tile` into `image`; returns the rays traced and the rays that hit.
  std::pair<uint64_t, uint64_t> render(const Tile& tile, Image& image) const {
    TileRays t = cameraRays(tile);
    std::vector<FieldSample> answers(t.rays.size());
    query(t, answers);
    uint64_t hits = 0;
    for (const FieldSample& a : answers)
      if (a.opacity > 0.0f) ++hits;
    size_t local = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x, ++local) {
        const size_t b = t.pixelStart[local], n = t.pixelStart[local + 1] - b;
        const int spp = samplesOf(x, y);
        if (spp == 0) continue;
        PixelRays p;
        p.answers = std::span<const FieldSample>(answers).subspan(b, n);
        p.rays = std::span<const FieldRay>(t.rays).subspan(b, n);
        if (spectral_) p.wavelengths = std::span<const SampledWavelengths>(t.wavelengths).subspan(b, n);
        p.weights = std::span<const float>(t.weights).subspan(b, n);
        p.spp = spp;
        p.spectral = spectral_;
        p.heroOnly = dispersive_;
        film_.resolvePixel(p, &image.at(x, y, 0));
      }
    return {t.rays.size(), hits};
  }

 private:
  int samplesOf(int x, int y) const {
    const std::vector<uint8_t>* full = settings_.fullSamples;
    if (!full || (*full)[size_t(y) * size_t(camera_.width()) + size_t(x)]) return settings_.spp;
    return std::min(settings_.sppElsewhere, settings_.spp);
  }

  TileRays cameraRays(const Tile& tile) const {
    const size_t nPix = size_t(tile.x1 - tile.x0) * size_t(tile.y1 - tile.y0);
    const size_t capacity = nPix * size_t(settings_.spp) * size_t(raysPerSample_);
    TileRays t;
    t.rays.reserve(capacity);
    t.wavelengths.reserve(spectral_ ? capacity : 0);
    t.weights.reserve(capacity);
    t.pixelStart.reserve(nPix + 1);
    std::vector<CameraSample> samples(size_t(settings_.spp) * kAttemptsPerSample);
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const uint64_t pixel = uint64_t(y) * uint64_t(camera_.width()) + uint64_t(x);
        const int spp = samplesOf(x, y);
        t.pixelStart.push_back(t.rays.size());
        if (spp > 0) pixelRays(x, y, pixel, spp, samples, t);
      }
    t.pixelStart.push_back(t.rays.size());
    return t;
  }

  // The pixel's first `spp` camera samples the camera does not vignette, drawn from its first
  // spp * kAttemptsPerSample points. The kept samples are numbered 0, 1, ... in order and
  // sample k takes point k's wavelength, so the wavelengths and the field's per-sample strata
  // (scene/path_random.h) stay whole where the lens vignettes some points (a real lens's pupil
  // box: 4 in 10 at f/4); taken from the surviving points, they left colour grain (CIEDE2000
  // between two seeds 8.3 against 3.3 with a thin lens, docs/speed-and-error.md).
  void pixelRays(int x, int y, uint64_t pixel, int spp, std::vector<CameraSample>& samples, TileRays& t) const {
    const size_t attempts = size_t(spp) * kAttemptsPerSample;
    sampler_.pixelSamples(pixel, std::span<CameraSample>(samples).first(attempts));
    int kept = 0;
    for (size_t a = 0; a < attempts && kept < spp; ++a) {
      CameraSample s = samples[a];
      s.wavelength = samples[size_t(kept)].wavelength;
      const Vec2 position(float(x) + s.pixelOffset.x, float(y) + s.pixelOffset.y);
      bool any = false;
      for (int k = 0; k < raysPerSample_; ++k) any |= addRay(position, s, pixel, kept, k, t);
      kept += any;
    }
  }

  // Ray k of camera sample `si`: the packet rotated by k / 4 so that ray k's own wavelength is
  // its hero; nothing (false) when the camera vignettes it.
  bool addRay(Vec2 position, const CameraSample& s, uint64_t pixel, int si, int k, TileRays& t) const {
    float uk = s.wavelength + float(k) / float(kNumWavelengths);
    if (uk >= 1.0f) uk -= 1.0f;
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(uk);
    Ray r;
    const float w = camera_.generateRay(position, s.lens, dispersive_ ? wl[0] : 550.0f, r);
    if (!(w > 0.0f)) return false;
    FieldRay fr{r.o, r.d, 0.0f, kInfinity, pixel, uint32_t(si * raysPerSample_ + k), uint32_t(si)};
    if (settings_.cameraToField) {
      const Point3d o = settings_.cameraToField->point(Point3d(r.o));
      const Vec3d d = settings_.cameraToField->vector(Vec3d(r.d));
      const double len = glm::length(d);
      if (!(len > 0.0) || !std::isfinite(len)) return false;
      fr.o = Point3(o);
      fr.d = Vec3(d / len);
    }
    t.rays.push_back(fr);
    if (spectral_) t.wavelengths.push_back(wl);
    t.weights.push_back(w / float(raysPerSample_));
    return true;
  }

  void query(const TileRays& t, std::vector<FieldSample>& answers) const {
    const size_t batch = size_t(std::max(1, settings_.raysPerBatch));
    for (size_t b = 0; b < t.rays.size(); b += batch) {
      const size_t n = std::min(t.rays.size() - b, batch);
      field_.query(std::span<const FieldRay>(t.rays).subspan(b, n),
                   spectral_ ? std::span<const SampledWavelengths>(t.wavelengths).subspan(b, n)
                             : std::span<const SampledWavelengths>(),
                   std::span<FieldSample>(answers).subspan(b, n), settings_.seed);
    }
  }

  const Field& field_;
  const CameraModel& camera_;
  const PixelSampler& sampler_;
  const Film& film_;
  const FieldRenderSettings& settings_;
  const bool spectral_, dispersive_;
  const int raysPerSample_;
};


// Before any pixel: the image, and the camera rays of the tiles in flight (one per worker thread),
// which grow with spp. Sample numbers are 32-bit (FieldRay::sample).
void checkRenderSize(int W, int H, size_t channels, int spp, const char* sppKey, int raysPerSample) {
  const std::string size = std::to_string(W) + " x " + std::to_string(H);
  checkAllocation("", "width/height", size, {{double(W) * H, double(channels) * sizeof(float)}},
                  "the " + size + " image of " + std::to_string(channels) + " channels");
  if (double(spp) * raysPerSample > double(UINT32_MAX))
    throw InputError("", sppKey, std::to_string(spp), "at most " + std::to_string(UINT32_MAX / uint32_t(raysPerSample)) +
                                                         " samples per pixel");
  const double perRay = sizeof(FieldRay) + sizeof(SampledWavelengths) + sizeof(float) + sizeof(FieldSample);
  const double tilePixels = double(std::min(W, kTileSize)) * std::min(H, kTileSize);
  checkAllocation("", sppKey, std::to_string(spp),
                  {{double(hardwareThreads()) * tilePixels * spp * raysPerSample, perRay}},
                  "the ray buffer of " + std::to_string(hardwareThreads()) + " tiles of " + std::to_string(int64_t(tilePixels)) +
                      " pixels in flight");
}

}  // namespace

FieldRender renderThroughCamera(const Field& field, const CameraModel& camera, const PixelSampler& sampler,
                                const Film& film, const FieldRenderSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  const int W = camera.width(), H = camera.height();
  const TileRenderer tiles(field, camera, sampler, film, settings);
  checkRenderSize(W, H, film.channels().size(), settings.spp, settings.sppKey, tiles.raysPerSample());
  if (settings.fullSamples && settings.fullSamples->size() != size_t(W) * size_t(H))
    throw std::invalid_argument("renderThroughCamera: the full-sample map is not width x height");
  FieldRender out;
  out.image = Image(W, H, film.channels());
  std::atomic<uint64_t> cameraRays{0}, hitRays{0};
  ProgressBar bar(settings.progressLabel, uint64_t(W) * H, settings.progress && ProgressBar::stderrIsTerminal());
  parallelForTiles(W, H, [&](const Tile& tile) {
    const auto [traced, hits] = tiles.render(tile, out.image);
    cameraRays += traced;
    hitRays += hits;
  }, &bar, kTileSize);
  bar.finish();
  out.stats.cameraRays = cameraRays;
  out.stats.hitRays = hitRays;
  out.stats.raysPerSample = tiles.raysPerSample();
  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace inim
