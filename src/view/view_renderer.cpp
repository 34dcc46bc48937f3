#include "view/view_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "spectral/sampled.h"
#include "view/qmc.h"

namespace inim {

const char* spectralSamplingName(SpectralSampling s) {
  return s == SpectralSampling::Primaries ? "primaries" : "visible";
}

const char* panelEstimatorName(PanelEstimator e) { return e == PanelEstimator::PointSample ? "point" : "footprint"; }

DisplayArea lensletArrayArea(const EiLayout& L, double P) {
  DisplayArea a;
  if (L.lensX.empty() || L.lensY.empty()) return a;
  a.x0 = L.lensX.front() - 0.5 * P;
  a.x1 = L.lensX.back() + 0.5 * P;
  a.y0 = L.lensY.back() - 0.5 * P;
  a.y1 = L.lensY.front() + 0.5 * P;
  return a;
}

double displayCoverage(const CameraModel& camera, const DisplayArea& area, int grid) {
  grid = std::max(1, grid);
  int hits = 0;
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      const Vec2 pix(float((i + 0.5) / grid * camera.width()), float((j + 0.5) / grid * camera.height()));
      Ray r;
      if (!(camera.generateRay(pix, Vec2(0.5f), 550.0f, r) > 0.0f) || !(r.d.z < 0.0f) || !(r.o.z > 0.0f)) continue;
      const Point3 p = r.o + (-r.o.z / r.d.z) * r.d;
      if (area.contains(p.x, p.y)) ++hits;
    }
  return double(hits) / double(grid * grid);
}

namespace {

constexpr uint64_t kScrambleStream = 0xFFFFFFFFFFFFull;  // sample slot of the Sobol scramble seeds
constexpr uint64_t kMlaSalt = 0x5EED0F3A11A0ull;         // salts the per-sample MLA stream
constexpr uint64_t kProbeSalt = 0x9B0BE5A17ull;          // salts the Jacobian probes' MLA stream
// Footprint estimator: finite-difference steps of the Jacobian probes (pixel units, and
// fractions of the lens sample square), and the cap on the box half-width (panel pixels).
constexpr float kProbePixelStep = 0.25f;
constexpr float kProbeLensStep = 0.05f;
constexpr double kMaxBoxHalfWidthPx = 8.0;

// Importance sampling of one primary's spectrum: a piecewise-constant pdf on 1 nm bins over
// 360-830 nm (bin mass = Simpson estimate of the spectrum over the bin, plus a floor of 1e-6
// of the largest, so the pdf is positive wherever the spectrum can be).
class ChannelSampler {
 public:
  template <class F>
  explicit ChannelSampler(F spectrum) {
    const int n = int(kLambdaMax - kLambdaMin);
    std::vector<double> mass(size_t(n), 0.0);
    double maxMass = 0.0;
    for (int b = 0; b < n; ++b) {
      const double a = kLambdaMin + b;
      mass[size_t(b)] = std::max(0.0, (double(spectrum(float(a))) + 4.0 * spectrum(float(a + 0.5)) +
                                       double(spectrum(float(a + 1.0)))) / 6.0);
      maxMass = std::max(maxMass, mass[size_t(b)]);
    }
    double total = 0.0;
    for (auto& m : mass) total += (m = std::max(m, 1e-6 * maxMass));
    cdf_.assign(size_t(n) + 1, 0.0f);
    pdf_.assign(size_t(n), 0.0f);
    double c = 0.0;
    for (int b = 0; b < n; ++b) {
      pdf_[size_t(b)] = float(mass[size_t(b)] / total);
      c += mass[size_t(b)] / total;
      cdf_[size_t(b) + 1] = float(c);
    }
    cdf_.back() = 1.0f;
  }
  float sample(float u, float& pdf) const {
    const int n = int(pdf_.size());
    int b = int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1;
    b = std::clamp(b, 0, n - 1);
    const float w = cdf_[size_t(b) + 1] - cdf_[size_t(b)];
    const float f = w > 0.0f ? std::clamp((u - cdf_[size_t(b)]) / w, 0.0f, 0x1.fffffep-1f) : 0.5f;
    pdf = pdf_[size_t(b)];
    return kLambdaMin + float(b) + f;
  }

 private:
  std::vector<float> cdf_, pdf_;
};

// A Spectrum view of one channel's full-drive radiance (for the exact non-dispersive integral).
class ChannelSpectrum final : public Spectrum {
 public:
  ChannelSpectrum(const PanelEmitter& e, int c) : e_(e), c_(c) {}
  float operator()(float l) const override { return e_.channelSpectrum(c_, l); }
  float maxValue() const override { return 0.0f; }

 private:
  const PanelEmitter& e_;
  int c_;
};

enum class Outcome { Background, Panel, Nothing };

// True when no ray of the tile can reach the active area (see ViewSettings::cullTiles).
bool tileMissesDisplay(const CameraModel& camera, const Tile& t, const DisplayArea& area, float frontZ) {
  const float xs[5] = {float(t.x0), float(t.x1), float(t.x0), float(t.x1), 0.5f * float(t.x0 + t.x1)};
  const float ys[5] = {float(t.y0), float(t.y0), float(t.y1), float(t.y1), 0.5f * float(t.y0 + t.y1)};
  const float us[3] = {0.02f, 0.5f, 0.98f};
  const float lambdas[3] = {550.0f, 450.0f, 650.0f};
  const int nl = camera.isDispersive() ? 3 : 1;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  int valid = 0;
  for (int i = 0; i < 5; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int l = 0; l < nl; ++l) {
          Ray r;
          if (!(camera.generateRay(Vec2(xs[i], ys[i]), Vec2(us[a], us[b]), lambdas[l], r) > 0.0f)) continue;
          if (!(r.d.z < 0.0f) || !(r.o.z > frontZ)) return false;  // grazing or behind: do not guess
          const double t0 = (double(frontZ) - r.o.z) / r.d.z;
          const double px = r.o.x + t0 * r.d.x, py = r.o.y + t0 * r.d.y;
          if (!std::isfinite(px) || !std::isfinite(py)) return false;
          lo[0] = std::min(lo[0], px);
          hi[0] = std::max(hi[0], px);
          lo[1] = std::min(lo[1], py);
          hi[1] = std::max(hi[1], py);
          ++valid;
        }
  if (valid == 0) return false;
  const double mx = 0.5 * (hi[0] - lo[0]) + 1.0, my = 0.5 * (hi[1] - lo[1]) + 1.0;
  return lo[0] - mx > area.x1 || hi[0] + mx < area.x0 || lo[1] - my > area.y1 || hi[1] + my < area.y0;
}

}  // namespace

ViewResult renderView(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                      const PanelEmitter& panel, const DisplayArea& area, const ViewSettings& s) {
  if (s.spp < 1) throw InputError("", "--spp", std::to_string(s.spp), "a whole number >= 1");
  if (!(s.backgroundY >= 0.0) || !std::isfinite(s.backgroundY))
    throw InputError("", "--background", std::to_string(s.backgroundY), "a luminance >= 0");
  const auto t0 = std::chrono::steady_clock::now();
  const int W = camera.width(), H = camera.height(), spp = s.spp;
  const bool camDisp = camera.isDispersive();
  const bool dispersive = camDisp || mla.isDispersive() || panel.isDispersive() || s.perWavelengthRays;
  const bool primaries = s.spectral == SpectralSampling::Primaries;
  const int raysPerSample = !dispersive ? 1 : primaries ? kNumPrimaries : kNumWavelengths;
  const float lambdaRef = float(s.referenceLambdaNm);
  const double bg = s.backgroundY;
  const float frontZ = mla.frontZ() + 0.01f;  // rays start just above the MLA

  // Exact per-channel spectral integrals (non-dispersive primaries path) and the samplers.
  Vec3d channelRgb[kNumPrimaries];
  std::vector<ChannelSampler> samplers;
  for (int c = 0; c < kNumPrimaries; ++c) {
    channelRgb[c] = sensor.cameraRgb(ChannelSpectrum(panel, c));
    samplers.emplace_back([&](float l) { return panel.channelSpectrum(c, l); });
  }

  const bool footprint = s.panelEstimator == PanelEstimator::Footprint;
  if (footprint && !(s.footprintScale >= 0.0 && std::isfinite(s.footprintScale)))
    throw InputError("", "footprintScale", std::to_string(s.footprintScale), "a finite scale >= 0");
  // Box half-width = 0.5 x scale x (row norm of the Jacobian) / sqrt(spp): see the header.
  const double boxScale = 0.5 * s.footprintScale / std::sqrt(double(spp));

  Image img(W, H, {"R", "G", "B"});
  std::atomic<uint64_t> nCam{0}, nDisp{0}, nPanel{0}, nEmit{0}, nCulled{0}, nProbe{0}, nProbeFail{0};
  const bool cull = s.cullTiles && bg == 0.0;
  ProgressBar bar("view", uint64_t(W) * H, s.progress && ProgressBar::stderrIsTerminal());

  parallelForTiles(W, H, [&](const Tile& tile) {
    if (cull && tileMissesDisplay(camera, tile, area, frontZ)) {
      nCulled += uint64_t(tile.x1 - tile.x0) * uint64_t(tile.y1 - tile.y0);
      return;  // the image is already 0 there
    }
    uint64_t cCam = 0, cDisp = 0, cPanel = 0, cEmit = 0, cProbe = 0, cProbeFail = 0;
    // Footprint: the half-widths (panel pixels) of this pixel's boxes.
    double hu = 0.0, hv = 0.0;
    // One traced ray from the camera to the panel at a wavelength. `em` gets the emission per
    // channel (PointSample: only the landing subpixel's channel is non-zero).
    auto trace = [&](const Ray& r, float lambda, Rng& rng, std::array<float, kNumPrimaries>& em,
                     float& throughput) -> Outcome {
      ++cCam;
      if (!(r.d.z < 0.0f) || !(r.o.z > frontZ)) return Outcome::Background;
      const float t = (frontZ - r.o.z) / r.d.z;
      const Point3 p = r.o + t * r.d;
      if (!area.contains(p.x, p.y)) return Outcome::Background;
      ++cDisp;
      Ray local{p, r.d, 0.0f, kInfinity};
      PanelArrival arr;
      if (!mla.traceToPanel(local, lambda, rng, arr)) return Outcome::Nothing;
      ++cPanel;
      throughput = arr.throughput;
      em = {0.0f, 0.0f, 0.0f};
      if (!footprint) {
        const PanelEmission e = panel.emit(arr, lambda);
        if (e.channel < 0 || e.weight == 0.0f) return Outcome::Nothing;
        em[size_t(e.channel)] = e.weight;
      } else {
        Vec2d uv;
        float factor = 0.0f;
        if (!panel.emissionPointPx(arr.p, arr.d, lambda, uv, factor)) return Outcome::Nothing;
        em = panel.boxAveragePx(uv.x - hu, uv.y - hv, uv.x + hu, uv.y + hv);
        for (auto& v : em) v *= factor;
        if (em[0] == 0.0f && em[1] == 0.0f && em[2] == 0.0f) return Outcome::Nothing;
      }
      ++cEmit;
      return Outcome::Panel;
    };
    // Footprint: where the ray of sample coordinates (pixel x, y, lens u, v) lands on the
    // emitter (panel pixels) at the reference wavelength, and through which lenslet. Every probe
    // of a pixel replays the same MLA random stream, so Fresnel choices agree between them.
    auto probe = [&](const float q[4], const Rng& rng0, Vec2d& uv, int& k, int& l) -> bool {
      ++cProbe;
      Ray r;
      if (!(camera.generateRay(Vec2(q[0], q[1]), Vec2(q[2], q[3]), lambdaRef, r) > 0.0f)) return false;
      if (!(r.d.z < 0.0f) || !(r.o.z > frontZ)) return false;
      const Point3 p = r.o + ((frontZ - r.o.z) / r.d.z) * r.d;
      if (!area.contains(p.x, p.y)) return false;
      Rng rng = rng0;
      PanelArrival arr;
      if (!mla.traceToPanel(Ray{p, r.d, 0.0f, kInfinity}, lambdaRef, rng, arr)) return false;
      float factor;
      if (!panel.emissionPointPx(arr.p, arr.d, lambdaRef, uv, factor)) return false;
      k = arr.lensletK;
      l = arr.lensletL;
      return true;
    };
    // The 2 x 4 Jacobian of the landing point with respect to the sample coordinates, by one-
    // sided differences from the pixel centre and the lens centre, each step taken toward the
    // side that stays in the base ray's lenslet. False when the base ray does not reach the panel.
    auto jacobian = [&](int x, int y, uint64_t pixel, double J[2][4]) -> bool {
      const Rng rng0 = Rng::forSample(s.seed ^ kProbeSalt, pixel, 0);
      const float base[4] = {float(x) + 0.5f, float(y) + 0.5f, 0.5f, 0.5f};
      Vec2d uv0;
      int k0, l0;
      if (!probe(base, rng0, uv0, k0, l0)) return false;
      for (int j = 0; j < 4; ++j) {
        bool ok = false;
        // +step, -step, then 1/16 of the step each way (pixels much larger than a lenslet).
        for (int attempt = 0; attempt < 4 && !ok; ++attempt) {
          const float sign = (attempt & 1) ? -1.0f : 1.0f;
          const float step = (j < 2 ? kProbePixelStep : kProbeLensStep) * (attempt < 2 ? 1.0f : 0.0625f);
          float q[4] = {base[0], base[1], base[2], base[3]};
          q[j] += sign * step;
          Vec2d uv;
          int k, l;
          if (!probe(q, rng0, uv, k, l) || k != k0 || l != l0) continue;
          J[0][j] = (uv.x - uv0.x) / double(sign * step);
          J[1][j] = (uv.y - uv0.y) / double(sign * step);
          ok = true;
        }
        if (!ok) {
          J[0][j] = J[1][j] = 0.0;
          ++cProbeFail;
        }
      }
      return true;
    };
    bool haveLastJ = false;  // the tile's last measured Jacobian, for pixels whose probe fails
    double lastJ[2][4] = {};

    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const uint64_t pixel = uint64_t(y) * uint64_t(W) + uint64_t(x);
        Rng scr = Rng::forSample(s.seed, pixel, kScrambleStream);
        uint32_t sc[SobolSequence::kDims];
        for (auto& v : sc) v = scr.nextU32();
        if (footprint) {
          double J[2][4];
          if (jacobian(x, y, pixel, J)) {
            std::memcpy(lastJ, J, sizeof J);
            haveLastJ = true;
          }
          hu = hv = 0.0;
          if (haveLastJ) {
            double su = 0.0, sv = 0.0;
            for (int j = 0; j < 4; ++j) {
              su += lastJ[0][j] * lastJ[0][j];
              sv += lastJ[1][j] * lastJ[1][j];
            }
            hu = std::min(boxScale * std::sqrt(su), kMaxBoxHalfWidthPx);
            hv = std::min(boxScale * std::sqrt(sv), kMaxBoxHalfWidthPx);
            if (!std::isfinite(hu) || !std::isfinite(hv)) hu = hv = 0.0;
          }
        }
        Vec3d acc(0.0);
        for (int si = 0; si < spp; ++si) {
          const uint32_t idx = uint32_t(si);
          const Vec2 pix(float(x) + SobolSequence::sample(idx, 0, sc[0]), float(y) + SobolSequence::sample(idx, 1, sc[1]));
          const Vec2 lens(SobolSequence::sample(idx, 2, sc[2]), SobolSequence::sample(idx, 3, sc[3]));
          const float ul = SobolSequence::sample(idx, 4, sc[4]);
          Rng rng = Rng::forSample(s.seed ^ kMlaSalt, pixel, uint64_t(si));
          std::array<float, kNumPrimaries> em{};
          float T = 1.0f;
          Ray ray;
          if (!dispersive) {
            const float w = camera.generateRay(pix, lens, lambdaRef, ray);
            if (!(w > 0.0f)) continue;
            const Outcome o = trace(ray, lambdaRef, rng, em, T);
            if (o == Outcome::Background) {
              acc += double(w) * bg;
            } else if (o == Outcome::Panel) {
              for (int c = 0; c < kNumPrimaries; ++c) {
                if (em[size_t(c)] == 0.0f) continue;
                const double k = double(w) * T * em[size_t(c)];
                if (primaries) {
                  acc += k * channelRgb[c];
                } else {
                  const SampledWavelengths wl = SampledWavelengths::sampleVisible(ul);
                  Vec3d sum(0.0);
                  for (int i = 0; i < kNumWavelengths; ++i)
                    if (wl.pdf()[i] > 0.0f)
                      sum += sensor.response(wl[i]) * (double(panel.channelSpectrum(c, wl[i])) / wl.pdf()[i]);
                  acc += k * sum / double(kNumWavelengths);
                }
              }
            }
            continue;
          }

          // Dispersive: one ray per primary (or per wavelength of the packet).
          float wShared = 0.0f;
          Ray shared;
          const bool shareRay = !camDisp;
          if (shareRay) {
            wShared = camera.generateRay(pix, lens, lambdaRef, shared);
            if (!(wShared > 0.0f)) continue;
          }
          SampledWavelengths wl;
          if (!primaries) wl = SampledWavelengths::sampleVisible(ul);
          for (int j = 0; j < raysPerSample; ++j) {
            float lambda, pdf;
            if (primaries) {
              lambda = samplers[size_t(j)].sample(ul, pdf);
            } else {
              lambda = wl[j];
              pdf = wl.pdf()[j];
            }
            if (!(pdf > 0.0f)) continue;
            float w = wShared;
            if (!shareRay) {
              w = camera.generateRay(pix, lens, lambda, ray);
              if (!(w > 0.0f)) continue;
            } else {
              ray = shared;
            }
            const Outcome o = trace(ray, lambda, rng, em, T);
            if (o == Outcome::Background) {
              acc += double(w) * bg / double(raysPerSample);
            } else if (o == Outcome::Panel) {
              for (int c = 0; c < kNumPrimaries; ++c) {
                if (em[size_t(c)] == 0.0f || (primaries && c != j)) continue;
                const double k = double(w) * T * em[size_t(c)] * panel.channelSpectrum(c, lambda) / pdf;
                acc += sensor.response(lambda) * (primaries ? k : k / double(kNumWavelengths));
              }
            }
          }
        }
        acc /= double(spp);
        for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(acc[c]);
      }
    nCam += cCam;
    nDisp += cDisp;
    nPanel += cPanel;
    nEmit += cEmit;
    nProbe += cProbe;
    nProbeFail += cProbeFail;
  }, &bar, 16);
  bar.finish();

  ViewResult r;
  r.image = std::move(img);
  r.stats.tracedRays = nCam;
  r.stats.displayRays = nDisp;
  r.stats.panelRays = nPanel;
  r.stats.emittingRays = nEmit;
  r.stats.culledPixels = nCulled;
  r.stats.probeRays = nProbe;
  r.stats.probeFailures = nProbeFail;
  r.stats.raysPerSample = raysPerSample;
  r.stats.dispersive = dispersive;
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace inim
