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
#include "view/convex_polygon.h"
#include "view/qmc.h"

namespace inim {

const char* spectralSamplingName(SpectralSampling s) {
  return s == SpectralSampling::Primaries ? "primaries" : "visible";
}

const char* panelEstimatorName(PanelEstimator e) {
  switch (e) {
    case PanelEstimator::PointSample: return "point";
    case PanelEstimator::Footprint: return "footprint";
    case PanelEstimator::Aperture: return "aperture";
    case PanelEstimator::Quadrature: return "quadrature";
  }
  return "?";
}

bool parsePanelEstimator(const std::string& name, PanelEstimator& out) {
  for (PanelEstimator e : {PanelEstimator::PointSample, PanelEstimator::Footprint, PanelEstimator::Aperture,
                           PanelEstimator::Quadrature})
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
  // The wavelength at cumulative mass u.
  float quantile(double u) const {
    float pdf;
    return sample(float(std::clamp(u, 0.0, double(0x1.fffffep-1f))), pdf);
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

// Quadrature: the camera's centre ray (through the aperture table's centroid) at the centre of
// a block of pixels, its crossing h of the MLA front plane and slope sl, and their Jacobians
// with respect to the pixel position (central differences of +-0.5 px, one-sided where a probe
// is blocked), so that pixel strata map to the MLA and the lenslet borders back to the sensor.
// Over a block (~0.1 mm of the sensor) the camera's mapping is affine to far below a pixel.
struct BlockCamera {
  bool ok = false;
  Vec2d pc{0.0}, h{0.0}, sl{0.0};
  double Jh[2][2] = {}, Js[2][2] = {};
  double w = 0.0, gw[2] = {0.0, 0.0};  // the centre ray's camera weight and its gradient (per px)
  // A dispersive camera: the centre ray's crossing and slope at each wavelength of `lambdas`,
  // minus the reference wavelength's (the lens's lateral colour, constant over a block).
  std::vector<Vec2d> dh, ds;
  // The centre ray at pixel position p (affine in p) at wavelength index i (-1: reference).
  void at(const Vec2d& p, int i, Vec2d& ho, Vec2d& so, double& wo) const {
    const Vec2d d = p - pc;
    ho = h + Vec2d(Jh[0][0] * d.x + Jh[0][1] * d.y, Jh[1][0] * d.x + Jh[1][1] * d.y);
    so = sl + Vec2d(Js[0][0] * d.x + Js[0][1] * d.y, Js[1][0] * d.x + Js[1][1] * d.y);
    if (i >= 0 && size_t(i) < dh.size()) ho += dh[size_t(i)], so += ds[size_t(i)];
    wo = w + gw[0] * d.x + gw[1] * d.y;
  }
};

bool centreCrossing(const ApertureSpace& space, const ApertureKernel& K, Vec2 pix, float lambda, float planeZ,
                    Vec2d& h, Vec2d& sl, uint64_t& rays, double* weight = nullptr) {
  Ray r;
  ++rays;
  const float w = space.ray(pix, K.centre, lambda, r);
  if (weight) *weight = w;
  if (!(w > 0.0f) || !(r.d.z < 0.0f) || !(r.o.z > planeZ)) return false;
  const double t = (double(planeZ) - r.o.z) / r.d.z;
  h = Vec2d(r.o.x + t * r.d.x, r.o.y + t * r.d.y);
  sl = Vec2d(r.d.x / -double(r.d.z), r.d.y / -double(r.d.z));
  return std::isfinite(h.x) && std::isfinite(h.y);
}

BlockCamera blockCamera(const ApertureSpace& space, const ApertureKernel& K, Vec2 pc, float lambda, float planeZ,
                        const std::vector<float>& lambdas, uint64_t& rays) {
  BlockCamera b;
  b.pc = Vec2d(pc);
  if (!centreCrossing(space, K, pc, lambda, planeZ, b.h, b.sl, rays, &b.w)) return b;
  for (int ax = 0; ax < 2; ++ax) {
    const Vec2 e = ax == 0 ? Vec2(0.5f, 0.0f) : Vec2(0.0f, 0.5f);
    Vec2d hp, sp, hm, sm;
    double wp, wm;
    const bool okp = centreCrossing(space, K, pc + e, lambda, planeZ, hp, sp, rays, &wp);
    const bool okm = centreCrossing(space, K, pc - e, lambda, planeZ, hm, sm, rays, &wm);
    double step = 1.0;
    if (!okp && !okm) return b;
    if (!okp) hp = b.h, sp = b.sl, wp = b.w, step = 0.5;
    if (!okm) hm = b.h, sm = b.sl, wm = b.w, step = 0.5;
    for (int i = 0; i < 2; ++i) {
      b.Jh[i][ax] = (hp[i] - hm[i]) / step;
      b.Js[i][ax] = (sp[i] - sm[i]) / step;
    }
    b.gw[ax] = (wp - wm) / step;
  }
  for (float l : lambdas) {
    Vec2d h, sl;
    if (!centreCrossing(space, K, pc, l, planeZ, h, sl, rays)) return b;
    b.dh.push_back(h - b.h);
    b.ds.push_back(sl - b.sl);
  }
  b.ok = true;
  return b;
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
  const bool quadrature = s.panelEstimator == PanelEstimator::Quadrature;
  const bool aperture = s.panelEstimator == PanelEstimator::Aperture;
  if (quadrature && !primaries)
    throw InputError("", "--spectral", "visible",
                     "primaries with --estimator quadrature (it integrates each primary's spectrum by quadrature)");
  std::unique_ptr<ApertureSpace> space;
  std::vector<ApertureKernel> kernels;
  std::vector<BlockCamera> blockCams;  // Quadrature: per block
  // Quadrature, dispersive: lambdaNodes wavelength nodes per primary, the middles of equal-mass
  // bins of the primary's spectrum, each with its bin's exact camera-RGB integral (the bins'
  // integrals sum to channelRgb[c]). Every piece of every stratum is traced at every node: a
  // node tied to a stratum would tie the colour to the position within the pixel (a bias that
  // more strata do not remove).
  const int lambdaNodes = s.wavelengthNodes;
  if (quadrature && (lambdaNodes < 1 || lambdaNodes > 64))
    throw InputError("", "--wavelength-nodes", std::to_string(lambdaNodes), "a whole number in 1..64");
  std::vector<float> binLambda[kNumPrimaries];
  std::vector<Vec3d> binRgb[kNumPrimaries];
  int strataX = 1, strataY = 1;
  if (quadrature) {
    for (int d = 1; d * d <= spp; ++d)
      if (spp % d == 0) strataX = d;
    strataY = spp / strataX;
  }
  // Auto block size: ~0.1 mm of the sensor (the pupil's shape, vignetting, changes little
  // over that), at most 32 pixels.
  const int kb = s.apertureBlock > 0 ? s.apertureBlock
                                     : std::clamp(int(std::lround(0.1 / std::max(1e-9, camera.sensor().pitchMm))), 1, 32);
  const int kbW = (W + kb - 1) / kb, kbH = (H + kb - 1) / kb;
  std::atomic<uint64_t> nApRays{0}, nApSamples{0}, nApFallbacks{0}, nQuadParts{0}, nSplit{0}, nLost{0};
  if (quadrature && dispersive) {
    for (int c = 0; c < kNumPrimaries; ++c) {
      Vec3d sum(0.0);
      for (int b = 0; b < lambdaNodes; ++b) {
        const double la = b == 0 ? double(kLambdaMin) : double(samplers[size_t(c)].quantile(double(b) / lambdaNodes));
        const double lb = b + 1 == lambdaNodes ? double(kLambdaMax)
                                               : double(samplers[size_t(c)].quantile(double(b + 1) / lambdaNodes));
        binLambda[c].push_back(samplers[size_t(c)].quantile((b + 0.5) / lambdaNodes));
        // Simpson on steps of <= 0.25 nm.
        const int n = 2 * std::max(1, int(std::ceil((lb - la) / 0.5)));
        Vec3d acc(0.0);
        for (int i = 0; i <= n && lb > la; ++i) {
          const double l = la + (lb - la) * i / n;
          const double wgt = (i == 0 || i == n) ? 1.0 : (i & 1) ? 4.0 : 2.0;
          acc += sensor.response(l) * (wgt * panel.channelSpectrum(c, float(l)));
        }
        binRgb[c].push_back(acc * ((lb - la) / (3.0 * n)));
        sum += binRgb[c].back();
      }
      // The bins' sum is the channel's integral up to the quadratures' rounding: make it exact.
      for (int i = 0; i < 3; ++i) {
        const double r = sum[i] != 0.0 ? channelRgb[c][i] / sum[i] : 0.0;
        for (auto& v : binRgb[c]) v[i] *= r;
      }
    }
  }
  // A dispersive camera: the block cameras' lateral colour at every node (primary-major).
  std::vector<float> nodeLambdas;
  if (quadrature && camDisp)
    for (int c = 0; c < kNumPrimaries; ++c) nodeLambdas.insert(nodeLambdas.end(), binLambda[c].begin(), binLambda[c].end());
  if (aperture || quadrature) {
    if (s.apertureGrid < 2 || s.apertureGrid > 64)
      throw InputError("", "apertureGrid", std::to_string(s.apertureGrid), "a grid size in 2..64");
    space = std::make_unique<ApertureSpace>(camera);
    kernels.resize(size_t(kbW) * size_t(kbH));
    if (quadrature) blockCams.resize(kernels.size());
    parallelForRange(int64_t(kernels.size()), [&](int64_t b0, int64_t b1) {
      uint64_t rays = 0;
      for (int64_t b = b0; b < b1; ++b) {
        const int bx = int(b % kbW), by = int(b / kbW);
        const float cx = 0.5f * float(bx * kb + std::min(W, (bx + 1) * kb));
        const float cy = 0.5f * float(by * kb + std::min(H, (by + 1) * kb));
        kernels[size_t(b)] = buildApertureKernel(*space, Vec2(cx, cy), lambdaRef, s.apertureGrid, rays, frontZ);
        if (quadrature && kernels[size_t(b)].valid())
          blockCams[size_t(b)] = blockCamera(*space, kernels[size_t(b)], Vec2(cx, cy), lambdaRef, frontZ, nodeLambdas, rays);
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
    uint64_t cApRays = 0, cApSamples = 0, cApFallbacks = 0, cQuadParts = 0, cSplit = 0, cLost = 0;
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
        if (!realMla->traceToPanel(Ray{p, r.d, 0.0f, kInfinity}, lambda, FresnelMode::Weighted, nullptr, arr))
          return false;
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
      double A[2][2] = {}, B[2][2] = {};  // d landing / d crossing, d landing / d slope (panel px per mm, per unit)
      std::vector<float> off;  // 2 per kernel point
    };
    auto measureJ = [&](const Vec2d& h0, const Vec2d& s0, const ApertureKernel& K, LensletJ& out) -> bool {
      Landing c;
      if (!landMla(h0, s0, lambdaRef, c)) return false;
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
          // Central where both probes stay in the centre ray's lenslet, else one-sided toward
          // the side that does (the centre ray near a lenslet border).
          const bool inP = okp && lp.k == c.k && lp.l == c.l, inM = okm && lm.k == c.k && lm.l == c.l;
          if (!inP && !inM) {
            good = false;
            break;
          }
          const Vec2d up = inP ? lp.uv : c.uv, um = inM ? lm.uv : c.uv;
          const double span = (inP ? e : 0.0) + (inM ? e : 0.0);
          double(&M)[2][2] = slope ? B : A;
          M[0][ax] = (up.x - um.x) / span;
          M[1][ax] = (up.y - um.y) / span;
        }
        if (good) {
          out.ok = true;
          break;
        }
      }
      if (!out.ok) return true;
      std::memcpy(out.A, A, sizeof A);
      std::memcpy(out.B, B, sizeof B);
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
    // The Jacobians of (block, the lenslet of landing L), measured on first need about the ray
    // that crosses the MLA front plane at h0 with slope s0; nullptr while they cannot be
    // measured there.
    auto lensletJacobian = [&](size_t block, const ApertureKernel& K, const Vec2d& h0, const Vec2d& s0,
                               const Landing& L) -> const LensletJ* {
      JEntry* entry = nullptr;
      for (auto& e : jCache)
        if (e.block == block && e.k == L.k && e.l == L.l) entry = &e;
      if (!entry) {
        jCache.push_back({block, L.k, L.l, 0, {}});
        entry = &jCache.back();
      }
      if (!entry->j.ok) {
        ++entry->tries;
        LensletJ m;
        if (measureJ(h0, s0, K, m) && m.ok && m.k == L.k && m.l == L.l) entry->j = std::move(m);
      }
      return entry->j.ok ? &entry->j : nullptr;
    };

    // Quadrature: adds piece Q (pixel coordinates) of a stratum of area aS to acc. Per primary
    // (dispersive) and wavelength node, the piece's centroid ray (the block's affine camera
    // model) is traced to the panel, and the lenslet's map is measured about the piece itself by
    // MLA-only probes (it is not affine over a lenslet: spherical aberration; and its pixel
    // Jacobian A Jh, with A = 1 - g/f for a thin lenslet, changes by ~6% between the blue and
    // the green primary, so it is measured at each wavelength):
    //   - M, landing per pixel: the secant over +-sqrt(3 var) of the piece along each axis,
    //     whose curvature also gives the mean landing's shift from the centroid's,
    //     (L+ + L- - 2 L0) / 6 (exact for a quadratic map);
    //   - B, landing per unit slope (once per piece): one-sided over the aperture's rms slope;
    //   - A, landing per mm of crossing point = (M - B Js) Jh^-1.
    // The aperture table's points map to panel offsets A dh + B ds, and each reads the exact
    // average of its channel's subpixels over the box with the variance of the piece's image
    // (its covariance through M). Pieces whose probes cross a lenslet border use the lenslet's
    // cached Jacobians instead.
    std::vector<float> pieceOff;
    // B is shared by the pieces of a stratum (it hardly varies over a pixel or with the
    // wavelength); haveB: measured.
    struct SlopeJacobian {
      bool haveB = false;
      double B[2][2] = {};
    };
    // Slots: the primaries (dispersive; 0..2) or the one slot (-1 for all).
    auto integratePiece = [&](const PolygonMoments& m, double aS, const ApertureKernel& K, const BlockCamera& bc,
                              size_t block, Vec3d& acc, int slot, SlopeJacobian& sj) {
      if (!(m.area > 0.0)) return;
      ++cQuadParts;
      const double frac = m.area / aS;
      const int slots = dispersive ? kNumPrimaries : 1, nodes = dispersive ? lambdaNodes : 1;
      const double det = bc.Jh[0][0] * bc.Jh[1][1] - bc.Jh[0][1] * bc.Jh[1][0];
      const double iJ[2][2] = {{bc.Jh[1][1] / det, -bc.Jh[0][1] / det}, {-bc.Jh[1][0] / det, bc.Jh[0][0] / det}};
      bool& haveB = sj.haveB;
      double(&B)[2][2] = sj.B;
      for (int j = slot < 0 ? 0 : slot; j < (slot < 0 ? slots : slot + 1); ++j)
        for (int node = 0; node < nodes; ++node) {
          const float lambda = dispersive ? binLambda[j][size_t(node)] : lambdaRef;
          Vec2d hc, sc;
          double w;
          bc.at(m.centroid, camDisp ? j * nodes + node : -1, hc, sc, w);
          ++cCam;
          Landing L;
          if (!(w > 0.0) || !landMla(hc, sc, lambda, L)) {
            ++cLost;
            continue;
          }
          ++cDisp;
          ++cPanel;
          auto sameLenslet = [&](const Landing& q) { return q.k == L.k && q.l == L.l; };
          double M[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
          Vec2d shift(0.0);
          bool ok = std::abs(det) > 0.0;
          for (int ax = 0; ax < 2 && ok; ++ax) {
            const double half = std::sqrt(3.0 * (ax == 0 ? m.cxx : m.cyy));
            if (!(half > 1e-6)) continue;
            Landing lp, lm;
            const Vec2d dh(bc.Jh[0][ax] * half, bc.Jh[1][ax] * half), ds(bc.Js[0][ax] * half, bc.Js[1][ax] * half);
            const bool inP = landMla(hc + dh, sc + ds, lambda, lp) && sameLenslet(lp);
            const bool inM = landMla(hc - dh, sc - ds, lambda, lm) && sameLenslet(lm);
            if (!inP && !inM) {
              ok = false;
              break;
            }
            const Vec2d up = inP ? lp.uv : L.uv, um = inM ? lm.uv : L.uv;
            const double span = (inP ? half : 0.0) + (inM ? half : 0.0);
            M[0][ax] = (up.x - um.x) / span;
            M[1][ax] = (up.y - um.y) / span;
            if (inP && inM) shift += (lp.uv + lm.uv - 2.0 * L.uv) / 6.0;
          }
          if (ok && !haveB) {
            const double es = std::max(K.rmsS, 1e-5);
            for (int ax = 0; ax < 2 && ok; ++ax) {
              const Vec2d dv = ax == 0 ? Vec2d(es, 0.0) : Vec2d(0.0, es);
              Landing bp;
              if (landMla(hc, sc + dv, lambda, bp) && sameLenslet(bp)) {
                B[0][ax] = (bp.uv.x - L.uv.x) / es;
                B[1][ax] = (bp.uv.y - L.uv.y) / es;
              } else if (landMla(hc, sc - dv, lambda, bp) && sameLenslet(bp)) {
                B[0][ax] = (L.uv.x - bp.uv.x) / es;
                B[1][ax] = (L.uv.y - bp.uv.y) / es;
              } else {
                ok = false;
              }
            }
            haveB = ok;
          }
          const float* off = nullptr;
          if (ok && haveB) {
            // A = (M - B Js) Jh^-1, then the table's offsets.
            double R[2][2], A[2][2];
            for (int a = 0; a < 2; ++a)
              for (int b = 0; b < 2; ++b) R[a][b] = M[a][b] - (B[a][0] * bc.Js[0][b] + B[a][1] * bc.Js[1][b]);
            for (int a = 0; a < 2; ++a)
              for (int b = 0; b < 2; ++b) A[a][b] = R[a][0] * iJ[0][b] + R[a][1] * iJ[1][b];
            pieceOff.resize(2 * K.points.size());
            for (size_t i = 0; i < K.points.size(); ++i) {
              const auto& q = K.points[i];
              pieceOff[2 * i] = float(A[0][0] * q.dhx + A[0][1] * q.dhy + B[0][0] * q.dsx + B[0][1] * q.dsy);
              pieceOff[2 * i + 1] = float(A[1][0] * q.dhx + A[1][1] * q.dhy + B[1][0] * q.dsx + B[1][1] * q.dsy);
            }
            off = pieceOff.data();
          } else if (const LensletJ* lj = lensletJacobian(block, K, hc, sc, L)) {
            // Probes across a lenslet border: the lenslet's cached Jacobians, no curvature shift.
            off = lj->off.data();
            shift = Vec2d(0.0);
            for (int a = 0; a < 2; ++a)
              for (int b = 0; b < 2; ++b)
                M[a][b] = lj->A[a][0] * bc.Jh[0][b] + lj->A[a][1] * bc.Jh[1][b] + lj->B[a][0] * bc.Js[0][b] +
                          lj->B[a][1] * bc.Js[1][b];
          } else {
            ++cApFallbacks;  // no Jacobians: the whole aperture at the landing point
          }
          double bu = 0.0, bv = 0.0;
          if (off) {
            const double vu = M[0][0] * M[0][0] * m.cxx + 2.0 * M[0][0] * M[0][1] * m.cxy + M[0][1] * M[0][1] * m.cyy;
            const double vv = M[1][0] * M[1][0] * m.cxx + 2.0 * M[1][0] * M[1][1] * m.cxy + M[1][1] * M[1][1] * m.cyy;
            bu = std::min(std::sqrt(3.0 * std::max(0.0, vu)), kMaxBoxHalfWidthPx);
            bv = std::min(std::sqrt(3.0 * std::max(0.0, vv)), kMaxBoxHalfWidthPx);
          }
          const size_t n = K.points.size();
          const double k = frac * w / K.centreWeight * L.T * L.factor;
          const double cu = L.uv.x + shift.x, cv = L.uv.y + shift.y;
          bool emitted = false;
          for (int c = 0; c < kNumPrimaries; ++c) {
            if (dispersive && c != j) continue;
            double e = 0.0;
            if (off) {
              for (size_t i = 0; i < n; ++i) {
                const double u = cu + off[2 * i], v = cv + off[2 * i + 1];
                e += double(K.points[i].w) * panel.channelBoxAveragePx(c, u - bu, v - bv, u + bu, v + bv);
              }
            } else {
              e = K.total * panel.channelDrivePx(c, L.uv.x, L.uv.y);
            }
            if (e == 0.0) continue;
            emitted = true;
            acc += (k * e) * (dispersive ? binRgb[c][size_t(node)] : channelRgb[c]);
          }
          if (emitted) ++cEmit;
        }
    };

    // The wavelength of slot j of a dispersive sample and its pdf: primary j's importance
    // sample, or the packet's j-th wavelength; false when it cannot carry light.
    auto slotWavelength = [&](int j, float ul, const SampledWavelengths& wl, float& lambda, float& pdf) {
      if (primaries) {
        lambda = samplers[size_t(j)].sample(ul, pdf);
      } else {
        lambda = wl[j];
        pdf = wl.pdf()[j];
      }
      return pdf > 0.0f;
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
        const ApertureKernel* K = nullptr;
        size_t kBlock = 0;
        if (aperture || quadrature) {
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
            if (dispersive && !slotWavelength(j, ul, wl, lambda, pdf)) continue;
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
                const Point3 pf = r.o + ((frontZ - r.o.z) / r.d.z) * r.d;
                const LensletJ* lj = lensletJacobian(kBlock, *K, Vec2d(pf.x, pf.y),
                                                     Vec2d(r.d.x / -double(r.d.z), r.d.y / -double(r.d.z)), L);
                if (lj) {
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
        // One sample of the point / footprint estimators (also the Quadrature fallback).
        auto pointSample = [&](int si) {
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
            if (!(w > 0.0f)) return;
            const Outcome o = trace(ray, lambdaRef, rng, em, T);
            if (o == Outcome::Background) {
              acc += double(w) * bg;
            } else if (o == Outcome::Panel) {
              accumulate(em, double(w) * T, lambdaRef, 1.0f, -1, ul);
            }
            return;
          }

          // Dispersive: one ray per primary (or per wavelength of the packet).
          float wShared = 0.0f;
          Ray shared;
          const bool shareRay = !camDisp;
          if (shareRay) {
            wShared = camera.generateRay(pix, lens, lambdaRef, shared);
            if (!(wShared > 0.0f)) return;
          }
          SampledWavelengths wl;
          if (!primaries) wl = SampledWavelengths::sampleVisible(ul);
          for (int j = 0; j < raysPerSample; ++j) {
            float lambda, pdf;
            if (!slotWavelength(j, ul, wl, lambda, pdf)) continue;
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
        };
        if (!aperture && !quadrature)
          for (int si = 0; si < spp; ++si) pointSample(si);
        // Quadrature: each stratum of the pixel (strataX x strataY of them) is cut along the
        // display's edge and the lenslet borders (mapped back to the sensor through the block's
        // affine camera model); each piece is integrated through its own lenslet: its centroid's
        // camera ray traced through the MLA (per primary, at the stratum's wavelength node,
        // Fresnel as a transmittance) gives the landing point, the aperture table's points map
        // to panel offsets through the lenslet's Jacobians (as in the Aperture estimator), and
        // each point reads the exact average of its channel's subpixels over a box with the
        // variance of the piece's image on the panel (its covariance through M = A Jh + B Js).
        if (quadrature) {
          const BlockCamera* bc = K && blockCams[kBlock].ok ? &blockCams[kBlock] : nullptr;
          const double aS = 1.0 / (double(strataX) * strataY);
          for (int si = 0; si < spp; ++si) {
            if (!bc) {
              ++cApFallbacks;
              pointSample(si);
              continue;
            }
            const int sx = si % strataX, sy = si / strataX;
            const ConvexPolygon S = ConvexPolygon::rect(x + double(sx) / strataX, y + double(sy) / strataY,
                                                        x + double(sx + 1) / strataX, y + double(sy + 1) / strataY);
            SlopeJacobian sj;
            // A dispersive camera images the lenslet borders (and the display's edge) at a
            // slightly different place per wavelength (lateral colour): then the stratum is cut
            // per primary, with that primary's centre-ray offsets.
            const int geometries = camDisp ? kNumPrimaries : 1;
            for (int gi = 0; gi < geometries; ++gi) {
              Vec2d h0 = bc->h, s0 = bc->sl;
              if (camDisp) {
                // The primary's lateral colour at its (middle) node.
                const size_t ci = size_t(gi * lambdaNodes + lambdaNodes / 2);
                if (ci < bc->dh.size()) h0 += bc->dh[ci], s0 += bc->ds[ci];
              }
              const int slot = camDisp ? gi : -1;
              // The part on the display (its active area on the MLA front plane).
              ConvexPolygon on = S;
              const Vec2d areaN[4] = {{-1.0, 0.0}, {1.0, 0.0}, {0.0, -1.0}, {0.0, 1.0}};
              const double areaC[4] = {-area.x0, area.x1, -area.y0, area.y1};
              for (int e = 0; e < 4; ++e) {
                Vec2d a;
                double c;
                pullBackHalfPlane(h0, bc->Jh, bc->pc, areaN[e], areaC[e], a, c);
                on = on.clipped(a, c);
              }
              const double aOn = on.empty() ? 0.0 : on.moments().area;
              if (bg > 0.0 && aOn < aS * (1.0 - 1e-9)) {
                // The rest sees the background: its camera weight is the aperture integral at
                // the stratum (the table's, scaled by the centre ray's weight there).
                Vec2d hb, sb;
                double wb;
                bc->at(S.centroid(), -1, hb, sb, wb);
                if (wb > 0.0) acc += (aS - aOn) / aS * (K->total * wb / K->centreWeight) * bg / double(geometries);
              }
              if (!(aOn > 1e-12 * aS)) continue;
              // The lenslet cells the part touches, found on the MLA's border plane (depth D).
              const double D = mla.cellDepth();
              auto toPlane = [&](const Vec2d& p, double depth) {
                const Vec2d d = p - bc->pc;
                return h0 + depth * s0 +
                       Vec2d((bc->Jh[0][0] + depth * bc->Js[0][0]) * d.x + (bc->Jh[0][1] + depth * bc->Js[0][1]) * d.y,
                             (bc->Jh[1][0] + depth * bc->Js[1][0]) * d.x + (bc->Jh[1][1] + depth * bc->Js[1][1]) * d.y);
              };
              std::array<LensletCell, 24> cells;
              int nCells = 0;
              auto addCell = [&](const LensletCell& c) {
                for (int i = 0; i < nCells; ++i)
                  if (cells[size_t(i)].k == c.k && cells[size_t(i)].l == c.l) return;
                if (nCells < int(cells.size())) cells[size_t(nCells++)] = c;
              };
              LensletCell cell;
              const Vec2d oc = on.centroid(), qc = toPlane(oc, D);
              if (mla.lensletCell(qc.x, qc.y, cell)) addCell(cell);
              for (int i = 0; i < on.n; ++i) {
                const Vec2d q = toPlane(on.v[size_t(i)], D);
                if (mla.lensletCell(q.x, q.y, cell)) addCell(cell);
              }
              if (nCells == 0) {  // no lattice: one piece
                integratePiece(on.moments(), aS, *K, *bc, kBlock, acc, slot, sj);
                continue;
              }
              double covered = 0.0;
              int pieces = 0;
              auto cutPieces = [&](int from, int to) {
                for (int i = from; i < to; ++i) {
                  const LensletCell& c = cells[size_t(i)];
                  ConvexPolygon q = on;
                  for (int e = 0; e < c.n && !q.empty(); ++e) {
                    // The border where the ray passes from this cap to the next: its depth
                    // where the part is along the edge (the caps meet lower toward the corners).
                    const double De = mla.cellBorderDepth(c, e, qc.x, qc.y);
                    const Vec2d hE = h0 + De * s0;
                    double JE[2][2];
                    for (int a = 0; a < 2; ++a)
                      for (int b = 0; b < 2; ++b) JE[a][b] = bc->Jh[a][b] + De * bc->Js[a][b];
                    Vec2d a;
                    double cc;
                    const Vec2d nrm(c.nx[size_t(e)], c.ny[size_t(e)]);
                    pullBackHalfPlane(hE, JE, bc->pc, nrm, c.h[size_t(e)] + nrm.x * c.cx + nrm.y * c.cy, a, cc);
                    q = q.clipped(a, cc);
                  }
                  if (q.empty()) continue;
                  const PolygonMoments mq = q.moments();
                  if (!(mq.area > 1e-12 * aS)) continue;
                  covered += mq.area;
                  ++pieces;
                  integratePiece(mq, aS, *K, *bc, kBlock, acc, slot, sj);
                }
              };
              cutPieces(0, nCells);
              if (covered < aOn * (1.0 - 1e-6)) {
                // A cell touched without holding a vertex of the part (a hexagon's corner
                // poking in): try the neighbours of the cells found.
                const int n0 = nCells;
                for (int i = 0; i < n0; ++i) {
                  const LensletCell c0 = cells[size_t(i)];
                  const double P = c0.pitch;
                  const double offs[12][2] = {{P, 0}, {-P, 0}, {0, P}, {0, -P}, {P, P}, {P, -P}, {-P, P}, {-P, -P},
                                              {0.5 * P, 0.866 * P}, {-0.5 * P, 0.866 * P}, {0.5 * P, -0.866 * P},
                                              {-0.5 * P, -0.866 * P}};
                  for (const auto& o : offs)
                    if (mla.lensletCell(c0.cx + o[0], c0.cy + o[1], cell)) addCell(cell);
                }
                cutPieces(n0, nCells);
              }
              if (pieces > 1 && gi == 0) ++cSplit;
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
    nQuadParts += cQuadParts;
    nSplit += cSplit;
    nLost += cLost;
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
  r.stats.quadratureParts = nQuadParts;
  r.stats.splitStrata = nSplit;
  r.stats.lostParts = nLost;
  r.stats.raysPerSample = raysPerSample;
  r.stats.dispersive = dispersive;
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace inim
