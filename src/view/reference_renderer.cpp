#include "view/reference_renderer.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <span>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "spectral/color.h"
#include "core/qmc.h"

namespace inim {

namespace {
constexpr uint64_t kScrambleStream = 0xFFFFFFFFFFFFull;
}  // namespace

ViewResult renderReference(const Field& field, const Transform& fieldToDisplay, const CameraModel& camera,
                           const CameraSensor& sensor, const ReferenceSettings& s) {
  if (s.spp < 1) throw InputError("", "--spp", std::to_string(s.spp), "a whole number >= 1");
  const auto t0 = std::chrono::steady_clock::now();
  const int W = camera.width(), H = camera.height(), spp = s.spp;
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  const bool camDisp = camera.isDispersive();
  const Transform toField = fieldToDisplay.inverse();
  // RGB fields: field RGB -> XYZ (linear colour spaces: the matrix of the basis vectors).
  glm::dmat3 rgbToCamera(1.0);
  if (!spectral) {
    glm::dmat3 toXyz;
    const auto& cs = ColorSystem::instance();
    for (int i = 0; i < 3; ++i) {
      Vec3 e(0.0f);
      e[i] = 1.0f;
      toXyz[i] = Vec3d(cs.convert(e, field.colorSpace(), "cie_xyz_d65"));
    }
    rgbToCamera = glm::inverse(sensor.colorFit().cameraToXyz) * toXyz;
  }

  Image img(W, H, {"R", "G", "B"});
  std::atomic<uint64_t> nCam{0}, nHit{0};
  ProgressBar bar("reference", uint64_t(W) * H, s.progress && ProgressBar::stderrIsTerminal());
  const size_t batch = size_t(std::max(1, s.raysPerBatch));

  parallelForTiles(W, H, [&](const Tile& tile) {
    const size_t nPix = size_t(tile.x1 - tile.x0) * size_t(tile.y1 - tile.y0);
    std::vector<FieldRay> rays;
    std::vector<SampledWavelengths> lambdas;
    std::vector<float> weights;
    std::vector<uint32_t> target;  // pixel within the tile
    rays.reserve(nPix * size_t(spp));
    lambdas.reserve(spectral ? rays.capacity() : 0);
    weights.reserve(rays.capacity());
    target.reserve(rays.capacity());
    uint32_t local = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x, ++local) {
        const uint64_t pixel = uint64_t(y) * uint64_t(W) + uint64_t(x);
        Rng scr = Rng::forSample(s.seed, pixel, kScrambleStream);
        uint32_t sc[SobolSequence::kDims];
        for (auto& v : sc) v = scr.nextU32();
        for (int si = 0; si < spp; ++si) {
          const uint32_t idx = uint32_t(si);
          const Vec2 pix(float(x) + SobolSequence::sample(idx, 0, sc[0]), float(y) + SobolSequence::sample(idx, 1, sc[1]));
          const Vec2 lens(SobolSequence::sample(idx, 2, sc[2]), SobolSequence::sample(idx, 3, sc[3]));
          const float uLambda = SobolSequence::sample(idx, 4, sc[4]);
          // A dispersive camera lens bends each wavelength its own way: one camera ray per
          // wavelength of the stratified packet, each carrying the packet rotated so that its
          // own wavelength is the hero (index 0), and weighted 1/4.
          const int nRays = camDisp ? kNumWavelengths : 1;
          for (int k = 0; k < nRays; ++k) {
            float uk = uLambda + float(k) / float(kNumWavelengths);
            if (uk >= 1.0f) uk -= 1.0f;
            const SampledWavelengths wl = SampledWavelengths::sampleVisible(uk);
            Ray r;
            const float w = camera.generateRay(pix, lens, camDisp ? wl[0] : 550.0f, r);
            if (!(w > 0.0f)) continue;
            const Point3d o = toField.point(Point3d(r.o));
            const Vec3d d = toField.vector(Vec3d(r.d));
            const double len = glm::length(d);
            if (!(len > 0.0) || !std::isfinite(len)) continue;
            rays.push_back({Point3(o), Vec3(d / len), 0.0f, kInfinity, pixel, uint32_t(si * nRays + k)});
            if (spectral) lambdas.push_back(wl);
            weights.push_back(w / float(nRays));
            target.push_back(local);
          }
        }
      }
    std::vector<FieldSample> out(rays.size());
    for (size_t b = 0; b < rays.size(); b += batch) {
      const size_t n = std::min(rays.size() - b, batch);
      field.query(std::span<const FieldRay>(rays).subspan(b, n),
                  spectral ? std::span<const SampledWavelengths>(lambdas).subspan(b, n)
                           : std::span<const SampledWavelengths>(),
                  std::span<FieldSample>(out).subspan(b, n), s.seed);
    }
    std::vector<Vec3d> acc(nPix, Vec3d(0.0));
    uint64_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const FieldSample& f = out[i];
      if (f.opacity > 0.0f) ++hits;
      Vec3d c(0.0);
      if (spectral) {
        const SampledWavelengths& wl = lambdas[i];
        if (camDisp) {
          // This ray's own (hero) wavelength only; a terminated packet carries 4x the hero.
          const float pdf = wl.pdf()[0];
          const double L0 = double(f.L[0]) / (f.secondaryTerminated ? double(kNumWavelengths) : 1.0);
          if (pdf > 0.0f && std::isfinite(L0)) c = sensor.response(wl[0]) * (L0 / pdf);
        } else {
          for (int k = 0; k < kNumWavelengths; ++k) {
            const float pdf = wl.pdf()[k];
            if (!(pdf > 0.0f) || !std::isfinite(f.L[k])) continue;
            c += sensor.response(wl[k]) * (double(f.L[k]) / pdf);
          }
          c /= double(kNumWavelengths);
        }
      } else {
        c = rgbToCamera * Vec3d(f.rgb);
      }
      if (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) acc[target[i]] += double(weights[i]) * c;
    }
    local = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x, ++local)
        for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(acc[local][c] / double(spp));
    nCam += rays.size();
    nHit += hits;
  }, &bar, 16);
  bar.finish();

  ViewResult r;
  r.image = std::move(img);
  r.stats.tracedRays = nCam;
  r.stats.emittingRays = nHit;
  r.stats.raysPerSample = camDisp ? kNumWavelengths : 1;
  r.stats.dispersive = camDisp;
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace inim
