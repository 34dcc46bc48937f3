#include "view/view_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "mla/real_mla.h"
#include "spectral/sampled.h"
#include "view/aperture_kernel.h"
#include "view/qmc.h"

namespace inim {

const char* spectralSamplingName(SpectralSampling s) {
  return s == SpectralSampling::Primaries ? "primaries" : "visible";
}

const char* panelEstimatorName(PanelEstimator e) {
  return e == PanelEstimator::PointSample ? "point" : e == PanelEstimator::Footprint ? "footprint" : "aperture";
}

bool parsePanelEstimator(const std::string& name, PanelEstimator& out) {
  for (PanelEstimator e : {PanelEstimator::PointSample, PanelEstimator::Footprint, PanelEstimator::Aperture})
    if (name == panelEstimatorName(e)) {
      out = e;
      return true;
    }
  return false;
}

DisplayArea lensletArrayArea(const EiLayout& L, double P) {
  DisplayArea a;
  if (L.lensX.empty() || L.lensY.empty()) return a;
  if (L.isHex()) {  // the hex lattice's bounding box (odd rows shifted, rows P sqrt(3)/2 apart)
    const auto b = L.activeArea();
    a.x0 = b.x0, a.x1 = b.x1, a.y0 = b.y0, a.y1 = b.y1;
    return a;
  }
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

PixelMask displayMask(const CameraModel& camera, const DisplayArea& area) {
  PixelMask m;
  m.width = camera.width();
  m.height = camera.height();
  m.on.assign(size_t(m.width) * m.height, 0);
  m.source = "display area";
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      Ray r;
      if (!(camera.generateRay(Vec2(x + 0.5f, y + 0.5f), Vec2(0.5f), 550.0f, r) > 0.0f) || !(r.d.z < 0.0f)) continue;
      const Point3 p = r.o + (-r.o.z / r.d.z) * r.d;
      m.on[size_t(y) * m.width + x] = area.contains(p.x, p.y) ? 1 : 0;
    }
  return m;
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

  // Aperture: one quadrature table of the camera aperture per block of pixels (built at the
  // block's centre pixel, reference wavelength), and the MLA traced with deterministic Fresnel.
  const bool aperture = s.panelEstimator == PanelEstimator::Aperture;
  std::unique_ptr<ApertureSpace> space;
  std::vector<ApertureKernel> kernels;
  // Auto block size: ~0.1 mm of the sensor (the pupil's shape, vignetting, changes little
  // over that), at most 32 pixels.
  const int kb = s.apertureBlock > 0 ? s.apertureBlock
                                     : std::clamp(int(std::lround(0.1 / std::max(1e-9, camera.sensor().pitchMm))), 1, 32);
  const int kbW = (W + kb - 1) / kb, kbH = (H + kb - 1) / kb;
  std::atomic<uint64_t> nApRays{0}, nApSamples{0}, nApFallbacks{0};
  if (aperture) {
    if (s.apertureGrid < 2 || s.apertureGrid > 64)
      throw InputError("", "apertureGrid", std::to_string(s.apertureGrid), "a grid size in 2..64");
    space = std::make_unique<ApertureSpace>(camera);
    kernels.resize(size_t(kbW) * size_t(kbH));
    parallelForRange(int64_t(kernels.size()), [&](int64_t b0, int64_t b1) {
      uint64_t rays = 0;
      for (int64_t b = b0; b < b1; ++b) {
        const int bx = int(b % kbW), by = int(b / kbW);
        const float cx = 0.5f * float(bx * kb + std::min(W, (bx + 1) * kb));
        const float cy = 0.5f * float(by * kb + std::min(H, (by + 1) * kb));
        kernels[size_t(b)] = buildApertureKernel(*space, Vec2(cx, cy), lambdaRef, s.apertureGrid, rays, frontZ);
      }
      nApRays += rays;
    }, nullptr, 1);
  }
  const RealMla* realMla = dynamic_cast<const RealMla*>(&mla);
  const bool weightedFresnel = realMla && realMla->options().fresnel == FresnelMode::Stochastic;

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
    uint64_t cApRays = 0, cApSamples = 0, cApFallbacks = 0;
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
    // Aperture: where the camera ray `r` (weight w) lands on the emitter, through the MLA with
    // Fresnel as a transmittance weight (no random reflection).
    struct Landing {
      Vec2d uv{0.0};
      float T = 0.0f, factor = 0.0f;
      int k = -1, l = -1;
    };
    auto landRay = [&](const Ray& r, float lambda, Landing& L) -> bool {
      if (!(r.d.z < 0.0f) || !(r.o.z > frontZ)) return false;
      const Point3 p = r.o + ((frontZ - r.o.z) / r.d.z) * r.d;
      if (!area.contains(p.x, p.y)) return false;
      PanelArrival arr;
      if (weightedFresnel) {
        MlaExit ex;
        if (!realMla->trace(Point3d(p), Vec3d(r.d), double(lambda), FresnelMode::Weighted, nullptr, ex)) return false;
        if (!(ex.d.z < 0.0)) return false;
        const double zp = realMla->panelZ();
        const double t = (zp - ex.p.z) / ex.d.z;
        if (!(t >= 0.0)) return false;
        arr.p = Point3(float(ex.p.x + t * ex.d.x), float(ex.p.y + t * ex.d.y), float(zp));
        arr.d = Vec3(ex.d);
        arr.throughput = float(ex.throughput);
        arr.lensletK = ex.capK;
        arr.lensletL = ex.capL;
      } else {
        Rng rng(0x5EEDull, 0);  // deterministic models ignore it
        if (!mla.traceToPanel(Ray{p, r.d, 0.0f, kInfinity}, lambda, rng, arr)) return false;
      }
      if (!panel.emissionPointPx(arr.p, arr.d, lambda, L.uv, L.factor)) return false;
      L.T = arr.throughput;
      L.k = arr.lensletK;
      L.l = arr.lensletL;
      return true;
    };
    // The MLA alone: a ray crossing the front plane at h with slope sl (d.x / -d.z, d.y / -d.z).
    auto landMla = [&](const Vec2d& h, const Vec2d& sl, float lambda, Landing& L) -> bool {
      ++cApRays;
      Ray r;
      r.o = Point3(float(h.x), float(h.y), frontZ);
      r.d = glm::normalize(Vec3(float(sl.x), float(sl.y), -1.0f));
      return landRay(Ray{r.o + 1e-3f * (-r.d), r.d, 0.0f, kInfinity}, lambda, L);
    };
    // Per pixel and lenslet: the MLA's Jacobians of the landing point (panel px) with respect to
    // the front-plane crossing (A) and the slope (B) of the pixel's centre ray, by central
    // differences at the kernel's rms spread (then a quarter of it), at the reference
    // wavelength; every probe must land through the centre ray's lenslet. The kernel's points
    // map to panel offsets A dh + B ds (stored), its sub-cell shift to (A shiftH + B shiftS).
    struct LensletJ {
      int k = -1, l = -1;
      bool ok = false;
      double shift[2][2] = {};
      std::vector<float> off;  // 2 per kernel point
    };
    auto measureJ = [&](Vec2 pix, const ApertureKernel& K, LensletJ& out) -> bool {
      ++cApRays;
      Ray r;
      if (!(space->ray(pix, K.centre, lambdaRef, r) > 0.0f)) return false;
      Landing c;
      if (!landRay(r, lambdaRef, c)) return false;
      const Point3 p = r.o + ((frontZ - r.o.z) / r.d.z) * r.d;
      const Vec2d h0(p.x, p.y), s0(r.d.x / -double(r.d.z), r.d.y / -double(r.d.z));
      out.k = c.k;
      out.l = c.l;
      out.ok = false;
      double A[2][2], B[2][2];
      for (double f : {1.0, 0.25}) {
        const double eh = f * std::max(K.rmsH, 0.002), es = f * std::max(K.rmsS, 1e-4);
        bool good = true;
        for (int m = 0; m < 4 && good; ++m) {
          const int ax = m & 1;
          const bool slope = m >= 2;
          const double e = slope ? es : eh;
          const Vec2d dv = ax == 0 ? Vec2d(e, 0.0) : Vec2d(0.0, e);
          Landing lp, lm;
          const bool okp = slope ? landMla(h0, s0 + dv, lambdaRef, lp) : landMla(h0 + dv, s0, lambdaRef, lp);
          const bool okm = slope ? landMla(h0, s0 - dv, lambdaRef, lm) : landMla(h0 - dv, s0, lambdaRef, lm);
          if (!okp || !okm || lp.k != c.k || lp.l != c.l || lm.k != c.k || lm.l != c.l) {
            good = false;
            break;
          }
          double(&M)[2][2] = slope ? B : A;
          M[0][ax] = (lp.uv.x - lm.uv.x) / (2.0 * e);
          M[1][ax] = (lp.uv.y - lm.uv.y) / (2.0 * e);
        }
        if (good) {
          out.ok = true;
          break;
        }
      }
      if (!out.ok) return true;
      out.off.resize(2 * K.points.size());
      for (size_t i = 0; i < K.points.size(); ++i) {
        const auto& q = K.points[i];
        out.off[2 * i] = float(A[0][0] * q.dhx + A[0][1] * q.dhy + B[0][0] * q.dsx + B[0][1] * q.dsy);
        out.off[2 * i + 1] = float(A[1][0] * q.dhx + A[1][1] * q.dhy + B[1][0] * q.dsx + B[1][1] * q.dsy);
      }
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          out.shift[i][j] = A[i][0] * K.shiftH[0][j] + A[i][1] * K.shiftH[1][j] + B[i][0] * K.shiftS[0][j] +
                            B[i][1] * K.shiftS[1][j];
      return true;
    };
    // The quadrature: sum over the kernel's points of weight x drive at the landing point
    // uv0 + offset_i + shift (sx, sy), per channel of `mask`.
    auto kernelSum = [&](const ApertureKernel& K, const LensletJ& lj, const Vec2d& uv0, double sx, double sy, int mask,
                         std::array<float, kNumPrimaries>& em) {
      double sum[kNumPrimaries] = {0.0, 0.0, 0.0};
      const double bu = uv0.x + lj.shift[0][0] * sx + lj.shift[0][1] * sy;
      const double bv = uv0.y + lj.shift[1][0] * sx + lj.shift[1][1] * sy;
      const size_t n = K.points.size();
      const float* off = lj.off.data();
      if (mask == 7) {
        for (size_t i = 0; i < n; ++i) {
          const PanelEmission e = panel.lookupPx(bu + off[2 * i], bv + off[2 * i + 1]);
          if (e.channel >= 0) sum[e.channel] += double(K.points[i].w) * e.weight;
        }
      } else {
        for (int c = 0; c < kNumPrimaries; ++c) {
          if (!(mask & (1 << c))) continue;
          for (size_t i = 0; i < n; ++i)
            sum[c] += double(K.points[i].w) * panel.channelDrivePx(c, bu + off[2 * i], bv + off[2 * i + 1]);
        }
      }
      for (int c = 0; c < kNumPrimaries; ++c) em[size_t(c)] = float(sum[c]);
    };
    // The tile's MLA Jacobians, one per (kernel block, lenslet): measured at the first sample
    // that lands through that lenslet (one thread renders a tile in a fixed order, so the cache
    // is deterministic); a failed measurement (probes straddling a lenslet border) is retried at
    // the next sample through that lenslet, and the failed sample falls back.
    struct JEntry {
      size_t block;
      int k, l, tries;
      LensletJ j;
    };
    std::vector<JEntry> jCache;

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
        const ApertureKernel* K = nullptr;
        size_t kBlock = 0;
        if (aperture) {
          kBlock = size_t(y / kb) * size_t(kbW) + size_t(x / kb);
          if (kernels[kBlock].valid()) K = &kernels[kBlock];
        }
        Vec3d acc(0.0);
        // Adds a traced ray's emission (em per channel, times k = camera weight x throughput) at
        // wavelength lambda (pdf) of slot j to acc: the one place every estimator turns emission
        // into camera RGB.
        auto accumulate = [&](const std::array<float, kNumPrimaries>& em, double k, float lambda, float pdf, int j,
                              float ul) {
          for (int c = 0; c < kNumPrimaries; ++c) {
            if (em[size_t(c)] == 0.0f) continue;
            if (!dispersive) {
              const double kc = k * em[size_t(c)];
              if (primaries) {
                acc += kc * channelRgb[c];
              } else {
                const SampledWavelengths wl = SampledWavelengths::sampleVisible(ul);
                Vec3d sum(0.0);
                for (int i = 0; i < kNumWavelengths; ++i)
                  if (wl.pdf()[i] > 0.0f)
                    sum += sensor.response(wl[i]) * (double(panel.channelSpectrum(c, wl[i])) / wl.pdf()[i]);
                acc += kc * sum / double(kNumWavelengths);
              }
            } else {
              if (primaries && c != j) continue;
              const double kc = k * em[size_t(c)] * panel.channelSpectrum(c, lambda) / pdf;
              acc += sensor.response(lambda) * (primaries ? kc : kc / double(kNumWavelengths));
            }
          }
        };
        for (int si = 0; aperture && si < spp; ++si) {
          const uint32_t idx = uint32_t(si);
          const Vec2 pix(float(x) + SobolSequence::sample(idx, 0, sc[0]), float(y) + SobolSequence::sample(idx, 1, sc[1]));
          const Vec2 lens(SobolSequence::sample(idx, 2, sc[2]), SobolSequence::sample(idx, 3, sc[3]));
          const float ul = SobolSequence::sample(idx, 4, sc[4]);
          Rng rng = Rng::forSample(s.seed ^ kMlaSalt, pixel, uint64_t(si));
          // The centre ray (shared by the wavelengths when the camera is not dispersive) and the
          // aperture-sampled fallback ray (made on first need).
          Ray rayC, rayU;
          float wC = 0.0f, wU = 0.0f;
          bool haveU = false;
          if (K && !camDisp) {
            wC = space->ray(pix, K->centre, lambdaRef, rayC);
          }
          SampledWavelengths wl;
          if (dispersive && !primaries) wl = SampledWavelengths::sampleVisible(ul);
          const int slots = dispersive ? raysPerSample : 1;
          for (int j = 0; j < slots; ++j) {
            float lambda = lambdaRef, pdf = 1.0f;
            if (dispersive) {
              if (primaries) {
                lambda = samplers[size_t(j)].sample(ul, pdf);
              } else {
                lambda = wl[j];
                pdf = wl.pdf()[j];
              }
              if (!(pdf > 0.0f)) continue;
            }
            const int mask = dispersive && primaries ? (1 << j) : 7;
            std::array<float, kNumPrimaries> em{};
            // Aperture quadrature: the centre ray lands in a lenslet whose Jacobian is known.
            bool background = false;
            if (K) {
              Ray r = rayC;
              float w = wC;
              if (camDisp) {
                w = space->ray(pix, K->centre, lambda, r);
              }
              Landing L;
              if (w > 0.0f) {
                // A centre ray that misses the display is not a failure of the quadrature: the
                // sampled aperture below handles the display's edge.
                const bool down = r.d.z < 0.0f && r.o.z > frontZ;
                const Point3 p = down ? r.o + ((frontZ - r.o.z) / r.d.z) * r.d : r.o;
                background = !down || !area.contains(p.x, p.y);
              }
              if (w > 0.0f && !background && landRay(r, lambda, L)) {
                const LensletJ* lj = nullptr;
                JEntry* entry = nullptr;
                for (auto& e : jCache)
                  if (e.block == kBlock && e.k == L.k && e.l == L.l) entry = &e;
                if (!entry) {
                  jCache.push_back({kBlock, L.k, L.l, 0, {}});
                  entry = &jCache.back();
                }
                if (!entry->j.ok) {
                  ++entry->tries;
                  LensletJ m;
                  if (measureJ(pix, *K, m) && m.ok && m.k == L.k && m.l == L.l) entry->j = std::move(m);
                }
                if (entry->j.ok) lj = &entry->j;
                if (lj && lj->ok) {
                  ++cCam;
                  ++cDisp;
                  ++cPanel;
                  ++cApSamples;
                  kernelSum(*K, *lj, L.uv, (double(lens.x) - 0.5) * K->cellW, (double(lens.y) - 0.5) * K->cellH, mask, em);
                  if (em[0] != 0.0f || em[1] != 0.0f || em[2] != 0.0f) {
                    ++cEmit;
                    accumulate(em, double(w) / K->centreWeight * L.T * L.factor, lambda, pdf, j, ul);
                  }
                  continue;
                }
              }
            }
            // Fallback: sample the aperture (the point estimator, stochastic Fresnel).
            if (K && !background) ++cApFallbacks;
            Ray r;
            float w;
            if (!camDisp) {
              if (!haveU) {
                wU = camera.generateRay(pix, lens, lambdaRef, rayU);
                haveU = true;
              }
              r = rayU;
              w = wU;
            } else {
              w = camera.generateRay(pix, lens, lambda, r);
            }
            if (!(w > 0.0f)) continue;
            float T = 1.0f;
            const Outcome o = trace(r, lambda, rng, em, T);
            if (o == Outcome::Background) acc += double(w) * bg / double(slots);
            else if (o == Outcome::Panel) accumulate(em, double(w) * T, lambda, pdf, j, ul);
          }
        }
        for (int si = 0; !aperture && si < spp; ++si) {
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
              accumulate(em, double(w) * T, lambdaRef, 1.0f, -1, ul);
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
              accumulate(em, double(w) * T, lambda, pdf, j, ul);
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
    nApRays += cApRays;
    nApSamples += cApSamples;
    nApFallbacks += cApFallbacks;
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
  r.stats.apertureRays = nApRays;
  r.stats.apertureSamples = nApSamples;
  r.stats.apertureFallbacks = nApFallbacks;
  r.stats.raysPerSample = raysPerSample;
  r.stats.dispersive = dispersive;
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace inim
