#include "synthesis/eia_synthesis.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>

#include "core/error.h"
#include "core/large_buffer.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "field/ray_table.h"
#include "rays/pinhole_rays.h"
#include "spectral/cmf_table.h"
#include "field/placement.h"
#include "synthesis/orthoscopic.h"

namespace inim {

namespace {

using Clock = std::chrono::steady_clock;

std::string num(double v, const char* fmt = "%.4g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Salt for the synthesis' own random stream (wavelength packets), so it never coincides with
// the stream a field derives from the same (seed, id, sample).
constexpr uint64_t kWavelengthSalt = 0x5EEDC0105ull;

void validate(const SynthesisSettings& s, const EiLayout& L) {
  if (s.displayRays && s.displayRays->size() != size_t(L.numRays()))
    throw InputError("", "display rays", std::to_string(s.displayRays->size()) + " rays",
                     "one ray per EI pixel of the layout (" + std::to_string(L.numRays()) + ")");
  if (s.spp < 1) throw InputError("", "spp", std::to_string(s.spp), "a whole number >= 1");
  if (!std::isfinite(s.vcpMm)) throw InputError("", "vcp_mm", num(s.vcpMm), "a finite distance in mm");
  if (!s.autoExposure && !(s.exposure > 0.0 && std::isfinite(s.exposure)))
    throw InputError("", "exposure", num(s.exposure), "a number > 0 or auto");
  if (s.autoExposure && !(s.autoPercentile > 0.0 && s.autoPercentile <= 100.0))
    throw InputError("", "auto_percentile", num(s.autoPercentile), "a percentile in (0, 100]");
}

// Where the scene lies in the display frame, from the field's bounds, and whether the VCP
// clips it.
void locateScene(const Field& field, const OrthoscopicQuery& oq, double vcpMm, SynthesisStats& st) {
  Point3d dlo, dhi;
  st.sceneBoundsKnown = boundsInFrame(field, oq.fieldToDisplay(), dlo, dhi);
  if (!st.sceneBoundsKnown) return;  // colours from elsewhere: nothing to locate
  st.sceneLo = dlo;
  st.sceneHi = dhi;
  st.sceneBehindVcp = dlo.z > vcpMm;
  st.sceneClipped = !st.sceneBehindVcp && dhi.z > vcpMm;
}

// The field queries of the display rays, `spp` per ray, and their mean colour as unexposed
// drive values (res.drive), with the hit statistics and the A, Z channels.
class DisplayRayQueries {
 public:
  DisplayRayQueries(const EiLayout& L, const Field& field, const SynthesisSettings& s, const OrthoscopicQuery& oq,
                    const PanelColor& color, SynthesisResult& res, std::vector<uint8_t>& hitFlag)
      : L_(L), field_(field), s_(s), oq_(oq), res_(res), hitFlag_(hitFlag),
        spectral_(field.encoding() == FieldEncoding::Spectral), depth_(field.answersDepth()),
        colorSpace_(field.colorSpace()), spp_(s.spp),
        toDrive_(color, DriveSettings{}), onPlaneTol_(float(0.5 * L.pixelMm)),
        batchRays_(std::max<int64_t>(1, s.raysPerBatch / s.spp)), cmf_(cmfTable()) {}

  // Display rays a batch.
  int64_t batchRays() const { return batchRays_; }

  // The rays of EIs [e0, e1) (EI order).
  void run(int64_t e0, int64_t e1) {
    const int64_t r0 = L_.rayBeginOfEiOrder(e0), r1 = L_.rayBeginOfEiOrder(e1);
    Batch& b = batches_.local();
    Counts local;
    for (int64_t b0 = r0; b0 < r1; b0 += batchRays_) {
      const int64_t b1 = std::min(r1, b0 + batchRays_);
      makeQueries(b0, b1, b);
      field_.query(b.rays, spectral_ ? std::span<const SampledWavelengths>(b.lambdas)
                                     : std::span<const SampledWavelengths>(),
                   b.out, s_.seed);
      resolve(b0, b1, b, local);
    }
    hits += local.hits;
    realRays += local.real;
    virtualRays += local.virtualRays;
  }

  // Display rays with a hit, and of those, in front of / behind the MLA plane.
  std::atomic<uint64_t> hits{0}, realRays{0}, virtualRays{0};

 private:
  struct Batch {
    std::vector<FieldRay> rays;
    std::vector<SampledWavelengths> lambdas;
    std::vector<FieldSample> out;
    std::vector<OrthoscopicQuery::Query> qs;  // one per display ray of the batch
    std::vector<Vec3> acc;
  };
  struct Counts {
    uint64_t hits = 0, real = 0, virtualRays = 0;
  };

  void makeQueries(int64_t b0, int64_t b1, Batch& b) const {
    const size_t nr = size_t(b1 - b0), nq = nr * size_t(spp_);
    b.rays.resize(nq);
    b.out.assign(nq, FieldSample{});
    b.lambdas.resize(spectral_ ? nq : 0);
    b.qs.resize(nr);
    for (int64_t r = b0; r < b1; ++r) {
      const size_t i = size_t(r - b0);
      const RayD pr = s_.displayRays ? RayD{Point3d(s_.displayRays->ray(size_t(r)).o),
                                            glm::normalize(Vec3d(s_.displayRays->ray(size_t(r)).d))}
                                     : pinholeRay(L_, r);
      for (int k = 0; k < spp_; ++k) {
        OrthoscopicQuery::Query q = oq_.make(pr.o, pr.d, uint64_t(r), uint32_t(k));
        b.rays[i * size_t(spp_) + size_t(k)] = q.ray;
        if (k == 0) b.qs[i] = q;
        if (spectral_) {
          // Wavelengths stratified over the ray's samples (and over the packet's 4).
          Rng rng = Rng::forSample(s_.seed ^ kWavelengthSalt, uint64_t(r), uint64_t(k));
          float u = (float(k) + rng.uniform()) / float(spp_);
          b.lambdas[i * size_t(spp_) + size_t(k)] = SampledWavelengths::sampleVisible(std::min(u, 0x1.fffffep-1f));
        }
      }
    }
  }

  void resolve(int64_t b0, int64_t b1, Batch& b, Counts& local) {
    const size_t nr = size_t(b1 - b0);
    b.acc.assign(nr, Vec3(0.0f));
    for (size_t i = 0; i < nr; ++i) b.acc[i] = resolveRay(b0 + int64_t(i), i, b, local);
    if (!spectral_) rgbToXYZInPlace(b.acc, colorSpace_);
    for (size_t i = 0; i < nr; ++i) {
      const Vec3 d = toDrive_.native(b.acc[i]);  // exposure and gamut come once all rays are in
      float* o = &res_.drive[size_t(b0 + int64_t(i)) * 3];
      o[0] = d.x, o[1] = d.y, o[2] = d.z;
    }
  }

  // The mean colour of display ray r (index i in the batch): XYZ, or the field's RGB.
  Vec3 resolveRay(int64_t r, size_t i, const Batch& b, Counts& local) {
    const OrthoscopicQuery::Query& q = b.qs[i];
    Vec3 sum(0.0f);
    float alpha = 0.0f, zSum = 0.0f;
    int hitCount = 0;
    if (q.ray.tFar >= 0.0f) {
      for (int k = 0; k < spp_; ++k) {
        const size_t j = i * size_t(spp_) + size_t(k);
        const FieldSample& fs = b.out[j];
        Vec3 c = spectral_ ? cmf_.toXYZ(fs.L, b.lambdas[j]) : fs.rgb;
        if (isFinite(c)) sum += c;
        if (std::isfinite(fs.opacity)) alpha += fs.opacity;
        if (!depth_) {
          hitCount += fs.opacity >= kHalfCoverage;  // no depth: coverage alone decides
        } else if (std::isfinite(fs.depth) && fs.opacity > 0.0f) {
          zSum += float(OrthoscopicQuery::hitZ(q, fs.depth));
          ++hitCount;
        }
      }
    }
    if (hitCount > 0) {
      hitFlag_[size_t(r)] = 1;
      ++local.hits;
      float z = depth_ ? zSum / float(hitCount) : 0.0f;  // Z stays empty without depth
      if (depth_ && z > onPlaneTol_) ++local.real;
      if (depth_ && z < -onPlaneTol_) ++local.virtualRays;
      if (s_.aovs) {
        PixelCoord p = eiaPixel(L_, rayAddress(L_, r));
        res_.eia.at(L_.panelCol0 + p.col, L_.panelRow0 + p.row, 3) = alpha / float(spp_);
        res_.eia.at(L_.panelCol0 + p.col, L_.panelRow0 + p.row, 4) = z;
      }
    }
    return sum / float(spp_);
  }

  const EiLayout& L_;
  const Field& field_;
  const SynthesisSettings& s_;
  const OrthoscopicQuery& oq_;
  SynthesisResult& res_;
  std::vector<uint8_t>& hitFlag_;
  const bool spectral_;
  const bool depth_;  // the field answers depths (else hits by coverage, no Z)
  const std::string colorSpace_;
  const int spp_;
  const FieldToDrive toDrive_;
  const float onPlaneTol_;
  const int64_t batchRays_;
  const CmfTable& cmf_;
  // One batch's buffers per thread, kept across calls: made afresh in every call (~5000 per
  // EIA, ~0.5 MB each, over glibc's mmap threshold), their pages were faulted in every time,
  // ~80 % of the page faults of `inim fig11`.
  tbb::enumerable_thread_specific<Batch> batches_;
};

// Exposure: fixed, or the one that maps the chosen percentile of the brightest channel of the
// pixels that see the scene to full drive.
double chooseExposure(const SynthesisSettings& s, const std::vector<float>& drive, const std::vector<uint8_t>& hitFlag,
                      uint64_t hitRays) {
  if (!s.autoExposure) return s.exposure;
  std::vector<float> Y;
  Y.reserve(size_t(hitRays));
  for (size_t r = 0; r < hitFlag.size(); ++r)
    if (hitFlag[r]) {
      const float* d = &drive[r * 3];
      Y.push_back(std::max({d[0], d[1], d[2]}));
    }
  double exposure = 1.0;
  if (!Y.empty()) {
    size_t k = std::min(Y.size() - 1, size_t(std::floor(s.autoPercentile / 100.0 * double(Y.size() - 1) + 0.5)));
    std::nth_element(Y.begin(), Y.begin() + std::ptrdiff_t(k), Y.end());
    if (Y[k] > 0.0f && std::isfinite(Y[k])) exposure = 1.0 / double(Y[k]);
  }
  return exposure;
}

// Exposure and white gains, then the gamut mapping, on every drive value; the EIA pixels.
void exposeAndMapGamut(const EiLayout& L, const PanelColor& color, const SynthesisSettings& s, SynthesisResult& res) {
  SynthesisStats& st = res.stats;
  const FieldToDrive toDrive(color, {st.exposureUsed, s.whiteBalanceD65, s.gamut, s.correction});
  Image& img = res.eia;
  std::mutex statsMutex;
  parallelForRange(
      L.numRays(),
      [&](int64_t a, int64_t b) {
        GamutStats local;
        for (int64_t r = a; r < b; ++r) {
          float* o = &res.drive[size_t(r) * 3];
          const Vec3 d = toDrive.fromNative(Vec3(o[0], o[1], o[2]), local);
          o[0] = d.x, o[1] = d.y, o[2] = d.z;
          PixelCoord p = eiaPixel(L, rayAddress(L, r));
          float* px = &img.data[(size_t(L.panelRow0 + p.row) * size_t(img.width) + size_t(L.panelCol0 + p.col)) *
                                size_t(img.numChannels())];
          px[0] = d.x, px[1] = d.y, px[2] = d.z;
        }
        std::lock_guard<std::mutex> lock(statsMutex);
        st.gamut += local;
      },
      nullptr, 1 << 14);
}

void addSceneWarnings(double vcpMm, SynthesisStats& st) {
  auto range = [](double a, double b) { return num(a, "%.3g") + " to " + num(b, "%.3g"); };
  if (st.sceneBehindVcp)
    st.warnings.push_back("the whole scene (display z " + range(st.sceneLo.z, st.sceneHi.z) +
                          " mm) lies in front of the VCP at z = " + num(vcpMm) +
                          " mm (closer to the viewer than the near plane): no query ray reaches it, the EIA is empty "
                          "(at most the field's background is seen); raise vcp_mm or move the scene with the "
                          "placement's translate_mm");
  else if (st.emptyEia)
    st.warnings.push_back("no query ray hit the scene" +
                          (st.sceneBoundsKnown ? " (display bounds x " + range(st.sceneLo.x, st.sceneHi.x) + ", y " +
                                                     range(st.sceneLo.y, st.sceneHi.y) + ", z " +
                                                     range(st.sceneLo.z, st.sceneHi.z) + " mm)"
                                               : std::string()) +
                          ": the EIA is empty (at most the field's background is seen)");
  if (st.sceneClipped)
    st.notes.push_back("part of the scene (up to z = " + num(st.sceneHi.z) + " mm) lies in front of the VCP at z = " +
                          num(vcpMm) + " mm and is clipped");
}

}  // namespace

void writeEiaExr(const Image& eia, double exposureUsed, const std::string& path) {
  writeImage(eia, path, {{kEiaExposureHeader, exposureUsed}}, ExrCompression::None);
}

SynthesisResult synthesizeEia(const EiLayout& L, const Panel& panel, const Field& field,
                              const SynthesisSettings& s) {
  const auto t0 = Clock::now();
  validate(s, L);
  const OrthoscopicQuery oq(s.placement.toDisplay(), s.vcpMm);
  const PanelColor color(panel);
  const int64_t N = L.numRays();
  // Rays per EI (hex EIs differ in size: the mean, for batching only).
  const int64_t perEi = L.isHex() ? std::max<int64_t>(1, N / std::max<int64_t>(1, L.numEis())) : L.raysPerEi();

  SynthesisResult res;
  SynthesisStats& st = res.stats;
  st.displayRays = uint64_t(N);
  st.queries = uint64_t(N) * uint64_t(s.spp);
  locateScene(field, oq, s.vcpMm, st);

  std::vector<std::string> channels = {"R", "G", "B"};
  if (s.aovs) channels.insert(channels.end(), {"A", "Z"});
  res.eia = Image(L.panelW, L.panelH, channels);
  res.drive = largeVector(size_t(N) * 3, 0.0f);
  std::vector<uint8_t> hitFlag = largeVector(size_t(N), uint8_t(0));

  ProgressBar bar("eia", uint64_t(N), s.progress && ProgressBar::stderrIsTerminal());
  DisplayRayQueries queries(L, field, s, oq, color, res, hitFlag);
  const int64_t grainEis = std::max<int64_t>(1, queries.batchRays() / std::max<int64_t>(1, perEi));
  const auto tq = Clock::now();
  parallelForRange(
      L.numEis(),
      [&](int64_t e0, int64_t e1) {
        queries.run(e0, e1);
        bar.add(uint64_t(L.rayBeginOfEiOrder(e1) - L.rayBeginOfEiOrder(e0)));
      },
      nullptr, grainEis);
  bar.finish();
  st.hitRays = queries.hits;
  st.realRays = queries.realRays;
  st.virtualRays = queries.virtualRays;
  st.emptyEia = st.hitRays == 0;
  st.hitDepthsKnown = field.answersDepth();

  st.exposureUsed = chooseExposure(s, res.drive, hitFlag, st.hitRays);
  exposeAndMapGamut(L, color, s, res);
  st.querySeconds = secondsSince(tq);
  addSceneWarnings(s.vcpMm, st);
  st.seconds = secondsSince(t0);
  return res;
}

Image eiaArea(const EiLayout& L, const Image& img, const std::string& file) {
  if (img.numChannels() < 3 || !((img.width == L.panelW && img.height == L.panelH) ||
                                 (img.width == L.eiaW && img.height == L.eiaH)))
    throw InputError(file, "EIA image",
                     std::to_string(img.width) + " x " + std::to_string(img.height) + " px, " +
                         std::to_string(img.numChannels()) + " channels",
                     "the panel size " + std::to_string(L.panelW) + " x " + std::to_string(L.panelH) +
                         " px or the EIA size " + std::to_string(L.eiaW) + " x " + std::to_string(L.eiaH) +
                         " px, with at least 3 channels (R, G, B)");
  const bool panelSized = img.width == L.panelW && img.height == L.panelH;
  const int x0 = panelSized ? L.panelCol0 : 0, y0 = panelSized ? L.panelRow0 : 0;
  Image out(L.eiaW, L.eiaH, {"R", "G", "B"});
  for (int y = 0; y < L.eiaH; ++y)
    for (int x = 0; x < L.eiaW; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = img.at(x0 + x, y0 + y, c);
  return out;
}

Image onPanel(const EiLayout& L, const Image& a) {
  Image out(L.panelW, L.panelH, a.channels);
  const int nc = a.numChannels();
  for (int y = 0; y < std::min(a.height, L.eiaH); ++y)
    for (int x = 0; x < std::min(a.width, L.eiaW); ++x)
      for (int c = 0; c < nc; ++c) out.at(L.panelCol0 + x, L.panelRow0 + y, c) = a.at(x, y, c);
  return out;
}

Image encodeForPanel(const Image& eia, const Eotf& eotf) {
  Image out(eia.width, eia.height, {"R", "G", "B"});
  const int nc = eia.numChannels();
  parallelForRange(int64_t(eia.width) * eia.height, [&](int64_t a, int64_t b) {
    for (size_t i = size_t(a); i < size_t(b); ++i)
      for (int c = 0; c < 3; ++c) {
        float v = c < nc ? eia.data[i * size_t(nc) + size_t(c)] : 0.0f;
        // Black (most of an EIA's border) skips the transfer function.
        out.data[i * 3 + size_t(c)] = v > 0.0f && std::isfinite(v) ? float(eotf.encode(std::min(v, 1.0f))) : 0.0f;
      }
  }, nullptr, 1 << 15);
  return out;
}

std::string summaryText(const SynthesisStats& st, GamutMapping mapping) {
  auto pct = [](uint64_t a, uint64_t b) { return b ? num(100.0 * double(a) / double(b), "%.2f") + " %" : std::string("0 %"); };
  std::string s;
  s += "rays:        " + std::to_string(st.displayRays) + " display rays x " +
       std::to_string(st.displayRays ? st.queries / st.displayRays : 0) + " spp = " + std::to_string(st.queries) +
       " queries\n";
  s += "time:        " + num(st.seconds, "%.2f") + " s (" + num(st.raysPerSecond() / 1e6, "%.3g") +
       " M queries/s)\n";
  s += "scene:       " + std::to_string(st.hitRays) + " rays hit it (" + pct(st.hitRays, st.displayRays) + "): " +
       (st.hitDepthsKnown ? std::to_string(st.realRays) + " real (z > 0), " + std::to_string(st.virtualRays) +
                                " virtual (z < 0), " + std::to_string(st.hitRays - st.realRays - st.virtualRays) +
                                " on the MLA plane\n"
                          : std::string("real / virtual unknown (the field gave no depth)\n"));
  s += "exposure:    " + num(st.exposureUsed, "%.5g") + "\n";
  s += "gamut:       " + std::to_string(st.gamut.outOfGamut) + " of " + std::to_string(st.gamut.pixels) +
       " pixels out of gamut (" + pct(st.gamut.outOfGamut, st.gamut.pixels) + "; " +
       std::to_string(st.gamut.negative) + " outside the primaries, " + std::to_string(st.gamut.overRange) +
       " above full drive; channel range " + num(st.gamut.minChannel) + " to " + num(st.gamut.maxChannel) +
       "), mapped by " + gamutName(mapping) +
       (mapping == GamutMapping::Clip ? " (each channel clamped to [0, 1])\n"
                                      : " (toward the grey of equal panel luminance)\n");
  for (const auto& n : st.notes) s += "note:        " + n + "\n";
  for (const auto& w : st.warnings) s += "warning:     " + w + "\n";
  return s;
}

}  // namespace inim
