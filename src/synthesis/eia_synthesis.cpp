#include "synthesis/eia_synthesis.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "rays/pinhole_rays.h"
#include "spectral/cmf_table.h"
#include "synthesis/orthoscopic.h"

namespace inim {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

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

}  // namespace

SynthesisResult synthesizeEia(const EiLayout& L, const Panel& panel, const Field& field,
                              const SynthesisSettings& s) {
  const auto t0 = Clock::now();
  validate(s, L);
  const OrthoscopicQuery oq(s.placement.toDisplay(), s.vcpMm);
  const PanelColor color(panel);
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  const std::string colorSpace = field.colorSpace();
  const int spp = s.spp;
  const int64_t N = L.numRays();
  // Rays per EI (hex EIs differ in size: the mean, for batching only).
  const int64_t perEi = L.isHex() ? std::max<int64_t>(1, N / std::max<int64_t>(1, L.numEis())) : L.raysPerEi();

  SynthesisResult res;
  SynthesisStats& st = res.stats;
  st.displayRays = uint64_t(N);
  st.queries = uint64_t(N) * uint64_t(spp);

  // Where the scene lies in the display frame, from the field's bounds.
  {
    Point3 lo, hi;
    field.bounds(lo, hi);
    Point3d dlo(std::numeric_limits<double>::infinity()), dhi(-std::numeric_limits<double>::infinity());
    for (int c = 0; c < 8; ++c) {
      Point3d p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
      Point3d q = oq.fieldToDisplay().point(p);
      dlo = glm::min(dlo, q);
      dhi = glm::max(dhi, q);
    }
    st.sceneLo = dlo;
    st.sceneHi = dhi;
    st.sceneBehindVcp = dlo.z > s.vcpMm;
    st.sceneClipped = !st.sceneBehindVcp && dhi.z > s.vcpMm;
  }

  std::vector<std::string> channels = {"R", "G", "B"};
  if (s.aovs) channels.insert(channels.end(), {"A", "Z"});
  res.eia = Image(L.panelW, L.panelH, channels);
  Image& img = res.eia;
  res.drive.assign(size_t(N) * 3, 0.0f);
  std::vector<uint8_t> hitFlag(size_t(N), 0);
  const glm::mat3 xyzToDrive = glm::mat3(color.xyzToDrive());
  const float onPlaneTol = float(0.5 * L.pixelMm);
  const CmfTable& cmf = cmfTable();

  std::atomic<uint64_t> hits{0}, realRays{0}, virtualRays{0};
  ProgressBar bar("eia", uint64_t(N), s.progress && ProgressBar::stderrIsTerminal());
  const int64_t batchRays = std::max<int64_t>(1, s.raysPerBatch / spp);  // display rays a batch
  const int64_t grainEis = std::max<int64_t>(1, batchRays / std::max<int64_t>(1, perEi));

  const auto tq = Clock::now();
  parallelForRange(
      L.numEis(),
      [&](int64_t e0, int64_t e1) {
        const int64_t r0 = L.rayBeginOfEiOrder(e0), r1 = L.rayBeginOfEiOrder(e1);
        std::vector<FieldRay> rays;
        std::vector<SampledWavelengths> lambdas;
        std::vector<FieldSample> out;
        std::vector<OrthoscopicQuery::Query> qs;  // one per display ray of the batch
        std::vector<Vec3> acc;
        uint64_t localHits = 0, localReal = 0, localVirtual = 0;
        for (int64_t b0 = r0; b0 < r1; b0 += batchRays) {
          const int64_t b1 = std::min(r1, b0 + batchRays);
          const size_t nr = size_t(b1 - b0), nq = nr * size_t(spp);
          rays.resize(nq);
          out.assign(nq, FieldSample{});
          lambdas.resize(spectral ? nq : 0);
          qs.resize(nr);
          for (int64_t r = b0; r < b1; ++r) {
            const size_t i = size_t(r - b0);
            const RayD pr = s.displayRays ? RayD{Point3d(s.displayRays->ray(size_t(r)).o),
                                                 glm::normalize(Vec3d(s.displayRays->ray(size_t(r)).d))}
                                          : pinholeRay(L, r);
            for (int k = 0; k < spp; ++k) {
              OrthoscopicQuery::Query q = oq.make(pr.o, pr.d, uint64_t(r), uint32_t(k));
              rays[i * size_t(spp) + size_t(k)] = q.ray;
              if (k == 0) qs[i] = q;
              if (spectral) {
                // Wavelengths stratified over the ray's samples (and over the packet's 4).
                Rng rng = Rng::forSample(s.seed ^ kWavelengthSalt, uint64_t(r), uint64_t(k));
                float u = (float(k) + rng.uniform()) / float(spp);
                lambdas[i * size_t(spp) + size_t(k)] = SampledWavelengths::sampleVisible(std::min(u, 0x1.fffffep-1f));
              }
            }
          }
          field.query(rays, spectral ? std::span<const SampledWavelengths>(lambdas)
                                     : std::span<const SampledWavelengths>(),
                      out, s.seed);
          acc.assign(nr, Vec3(0.0f));
          for (size_t i = 0; i < nr; ++i) {
            const int64_t r = b0 + int64_t(i);
            const OrthoscopicQuery::Query& q = qs[i];
            Vec3 sum(0.0f);
            float alpha = 0.0f, zSum = 0.0f;
            int zCount = 0;
            if (q.ray.tFar >= 0.0f) {
              for (int k = 0; k < spp; ++k) {
                const size_t j = i * size_t(spp) + size_t(k);
                const FieldSample& fs = out[j];
                Vec3 c = spectral ? cmf.toXYZ(fs.L, lambdas[j]) : fs.rgb;
                if (isFinite(c)) sum += c;
                if (std::isfinite(fs.opacity)) alpha += fs.opacity;
                if (std::isfinite(fs.depth) && fs.opacity > 0.0f) {
                  zSum += float(OrthoscopicQuery::hitZ(q, fs.depth));
                  ++zCount;
                }
              }
            }
            acc[i] = sum / float(spp);
            if (zCount > 0) {
              hitFlag[size_t(r)] = 1;
              ++localHits;
              float z = zSum / float(zCount);
              if (z > onPlaneTol) ++localReal;
              if (z < -onPlaneTol) ++localVirtual;
              if (s.aovs) {
                PixelCoord p = eiaPixel(L, rayAddress(L, r));
                img.at(L.panelCol0 + p.col, L.panelRow0 + p.row, 3) = alpha / float(spp);
                img.at(L.panelCol0 + p.col, L.panelRow0 + p.row, 4) = z;
              }
            }
          }
          if (!spectral) rgbToXYZInPlace(acc, colorSpace);
          for (size_t i = 0; i < nr; ++i) {
            Vec3 d = xyzToDrive * acc[i];
            float* o = &res.drive[size_t(b0 + int64_t(i)) * 3];
            o[0] = d.x, o[1] = d.y, o[2] = d.z;
          }
        }
        hits += localHits;
        realRays += localReal;
        virtualRays += localVirtual;
        bar.add(uint64_t(r1 - r0));
      },
      nullptr, grainEis);
  bar.finish();
  st.hitRays = hits;
  st.realRays = realRays;
  st.virtualRays = virtualRays;
  st.emptyEia = st.hitRays == 0;

  // Exposure: fixed, or the one that maps the chosen percentile of the brightest channel of
  // the pixels that see the scene to full drive.
  const Vec3 lumW = Vec3(color.luminanceWeights());
  double exposure = s.exposure;
  if (s.autoExposure) {
    std::vector<float> Y;
    Y.reserve(size_t(st.hitRays));
    for (int64_t r = 0; r < N; ++r)
      if (hitFlag[size_t(r)]) {
        const float* d = &res.drive[size_t(r) * 3];
        Y.push_back(std::max({d[0], d[1], d[2]}));
      }
    exposure = 1.0;
    if (!Y.empty()) {
      size_t k = std::min(Y.size() - 1, size_t(std::floor(s.autoPercentile / 100.0 * double(Y.size() - 1) + 0.5)));
      std::nth_element(Y.begin(), Y.begin() + std::ptrdiff_t(k), Y.end());
      if (Y[k] > 0.0f && std::isfinite(Y[k])) exposure = 1.0 / double(Y[k]);
    }
  }
  st.exposureUsed = exposure;
  Vec3 gains = Vec3(float(exposure));
  if (s.whiteBalanceD65) gains *= Vec3(color.d65WhiteGains());

  std::mutex statsMutex;
  parallelForRange(
      N,
      [&](int64_t a, int64_t b) {
        GamutStats local;
        for (int64_t r = a; r < b; ++r) {
          float* o = &res.drive[size_t(r) * 3];
          Vec3 d = Vec3(o[0], o[1], o[2]) * gains;
          mapToGamut(d, lumW, s.gamut, local);
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
  st.querySeconds = std::chrono::duration<double>(Clock::now() - tq).count();

  auto range = [](double a, double b) { return num(a, "%.3g") + " to " + num(b, "%.3g"); };
  if (st.sceneBehindVcp)
    st.warnings.push_back("the whole scene (display z " + range(st.sceneLo.z, st.sceneHi.z) +
                          " mm) lies in front of the VCP at z = " + num(s.vcpMm) +
                          " mm (closer to the viewer than the near plane): no query ray reaches it, the EIA is empty "
                          "(at most the field's background is seen); raise vcp_mm or move the scene with the "
                          "placement's translate_mm");
  else if (st.emptyEia)
    st.warnings.push_back("no query ray hit the scene (display bounds x " + range(st.sceneLo.x, st.sceneHi.x) +
                          ", y " + range(st.sceneLo.y, st.sceneHi.y) + ", z " + range(st.sceneLo.z, st.sceneHi.z) +
                          " mm): the EIA is empty (at most the field's background is seen)");
  if (st.sceneClipped)
    st.notes.push_back("part of the scene (up to z = " + num(st.sceneHi.z) + " mm) lies in front of the VCP at z = " +
                          num(s.vcpMm) + " mm and is clipped");
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
       std::to_string(st.realRays) + " real (z > 0), " + std::to_string(st.virtualRays) + " virtual (z < 0), " +
       std::to_string(st.hitRays - st.realRays - st.virtualRays) + " on the MLA plane\n";
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
