#include "render/renderer.h"

#include <chrono>
#include <vector>

#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace inim {

RenderResult renderField(const Field& field, const ThinLensCamera& camera, const RenderSettings& s) {
  const int W = camera.spec().width, H = camera.spec().height, spp = std::max(1, s.spp);
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  Image img(W, H, {"R", "G", "B", "A", "Z"});
  const Mat3 toRec709 = ColorSystem::xyzToRec709();
  auto t0 = std::chrono::steady_clock::now();
  ProgressBar bar("render", uint64_t(W) * H, s.progress && ProgressBar::stderrIsTerminal());
  constexpr int kTile = 16;

  parallelForTiles(W, H, [&](const Tile& tile) {
    const int nPix = (tile.x1 - tile.x0) * (tile.y1 - tile.y0);
    std::vector<FieldRay> rays(size_t(nPix) * spp);
    std::vector<SampledWavelengths> lambdas(spectral ? rays.size() : 0);
    std::vector<FieldSample> out(rays.size());
    size_t k = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        uint64_t pixel = uint64_t(y) * W + x;
        for (int sIdx = 0; sIdx < spp; ++sIdx, ++k) {
          // The camera's own stream: salted so it is independent of the field's stream.
          Rng rng = Rng::forSample(s.seed ^ 0xC0FFEEull, pixel, sIdx);
          Vec2 jitter(rng.uniform(), rng.uniform()), lens(rng.uniform(), rng.uniform());
          Ray r = camera.generateRay(x + jitter.x, y + jitter.y, lens);
          rays[k] = {r.o, r.d, 0.0f, kInfinity, pixel, uint32_t(sIdx)};
          if (spectral) lambdas[k] = SampledWavelengths::sampleVisible(rng.uniform());
        }
      }
    for (size_t b = 0; b < rays.size(); b += size_t(s.raysPerBatch)) {
      size_t n = std::min(rays.size() - b, size_t(s.raysPerBatch));
      field.query(std::span(rays).subspan(b, n),
                  spectral ? std::span<const SampledWavelengths>(lambdas).subspan(b, n)
                           : std::span<const SampledWavelengths>(),
                  std::span(out).subspan(b, n), s.seed);
    }
    k = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        Vec3 acc(0.0f);
        float alpha = 0.0f, depthSum = 0.0f;
        int depthCount = 0;
        for (int sIdx = 0; sIdx < spp; ++sIdx, ++k) {
          const FieldSample& fs = out[k];
          Vec3 c = spectral ? toRec709 * sampledToXYZ(fs.L, lambdas[k]) : fs.rgb;
          if (isFinite(c)) acc += c;
          alpha += fs.opacity;
          if (std::isfinite(fs.depth)) {
            depthSum += fs.depth;
            ++depthCount;
          }
        }
        acc /= float(spp);
        img.at(x, y, 0) = acc.x;
        img.at(x, y, 1) = acc.y;
        img.at(x, y, 2) = acc.z;
        img.at(x, y, 3) = alpha / float(spp);
        img.at(x, y, 4) = depthCount ? depthSum / float(depthCount) : 0.0f;
      }
  }, &bar, kTile);
  bar.finish();

  if (!spectral && field.colorSpace() != "lin_rec709")
    ColorSystem::instance().convertImage(img, field.colorSpace(), "lin_rec709");
  RenderResult res;
  res.image = std::move(img);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.raysTraced = uint64_t(W) * H * spp;
  return res;
}

Image encodeSRGB(const Image& lin) {
  Image rgb(lin.width, lin.height, {"R", "G", "B"});
  for (int y = 0; y < lin.height; ++y)
    for (int x = 0; x < lin.width; ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = std::max(0.0f, lin.at(x, y, c));
  ColorSystem::instance().convertImage(rgb, "lin_rec709", "srgb");
  return rgb;
}

}  // namespace inim
