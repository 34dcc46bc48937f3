#include "triads/triads.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"

namespace inim {

TriadWavelengths paperTriadWavelengths() { return {{656.0, 566.0, 471.0}, "paper (656/566/471 nm)"}; }

TriadWavelengths triadWavelengths(const Panel& panel, const std::string& choice) {
  if (choice == "paper") return paperTriadWavelengths();
  if (choice == "zemax-sequential") return {{620.0, 525.0, 460.0}, "paper's sequential model (620/525/460 nm)"};
  if (choice != "panel")
    throw InputError("", "triad_wavelengths", "\"" + choice + "\"", "one of: panel, paper, zemax-sequential");
  TriadWavelengths w;
  for (int c = 0; c < 3; ++c) w.nm[size_t(c)] = primaryPeakNm(panel.primaries[size_t(c)]);
  w.source = "panel primary peaks";
  return w;
}

namespace {

// Exactly three finite numbers separated by commas (spaces allowed around them).
bool parseThreeNumbers(const std::string& text, std::array<double, 3>& v) {
  const char* p = text.c_str();
  for (size_t i = 0; i < 3; ++i) {
    char* end = nullptr;
    v[i] = std::strtod(p, &end);
    if (end == p || !std::isfinite(v[i])) return false;
    p = end;
    while (*p == ' ') ++p;
    if (i < 2 && *p++ != ',') return false;
  }
  return *p == '\0';
}

std::string wavelengthText(double nm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", nm);
  return buf;
}

}  // namespace

TriadWavelengths parseTriadWavelengths(const Panel& panel, const std::string& text, const std::string& key) {
  if (text.find(',') == std::string::npos) {
    try {
      return triadWavelengths(panel, text);
    } catch (const InputError&) {
      throw InputError("", key, "\"" + text + "\"", "panel, paper, zemax-sequential or three wavelengths R,G,B in nm");
    }
  }
  TriadWavelengths w;
  if (!parseThreeNumbers(text, w.nm))
    throw InputError("", key, "\"" + text + "\"", "three comma-separated wavelengths R,G,B in nm");
  for (double nm : w.nm)
    if (!(nm >= kLambdaMin && nm <= kLambdaMax)) throw InputError("", key, "\"" + text + "\"", "wavelengths in 360-830 nm");
  const auto& [r, g, b] = w.nm;
  if (std::abs(r - g) < 2.0 || std::abs(g - b) < 2.0 || std::abs(r - b) < 2.0)
    throw InputError("", key, "\"" + text + "\"", "three wavelengths at least 2 nm apart");
  // Written into SDF descriptions: the format is part of the output.
  w.source = "given (" + wavelengthText(r) + "/" + wavelengthText(g) + "/" + wavelengthText(b) + " nm)";
  return w;
}

void makeTriad(const Ray& r, const float* drive, const TriadWavelengths& w, float fluxScale, SdfRay out[3]) {
  for (int c = 0; c < 3; ++c)
    out[c] = {r.o.x, r.o.y, r.o.z, -r.d.x, -r.d.y, -r.d.z, drive[c] * fluxScale, float(w.nm[size_t(c)] * 1e-3)};
}

static void checkDrive(const RaySet& rays, const std::vector<float>& drive) {
  if (drive.size() != rays.size() * 3)
    throw InputError("", "drive values", std::to_string(drive.size()),
                     "3 values (R, G, B) for each of the " + std::to_string(rays.size()) + " rays");
}

std::vector<SdfRay> expandTriads(const RaySet& rays, const std::vector<float>& drive, const TriadWavelengths& w,
                                 const TriadOptions& options) {
  checkDrive(rays, drive);
  std::vector<SdfRay> out(rays.size() * 3);
  parallelForRange(int64_t(rays.size()), [&](int64_t a, int64_t b) {
    for (int64_t i = a; i < b; ++i)
      makeTriad(rays.ray(size_t(i)), &drive[size_t(i) * 3], w, options.fluxScale, &out[size_t(i) * 3]);
  });
  if (options.skipZeroFlux)
    out.erase(std::remove_if(out.begin(), out.end(), [](const SdfRay& r) { return r.flux == 0.0f; }), out.end());
  return out;
}

uint64_t writeTriadSdf(const std::string& path, const RaySet& rays, const std::vector<float>& drive,
                       const TriadWavelengths& w, const TriadOptions& options, ProgressBar* progress) {
  checkDrive(rays, drive);
  SdfHeader h;
  h.setDescription(options.description);
  SdfWriter writer(path, h);
  constexpr size_t kChunk = 1 << 16;  // display rays per chunk: 6 MiB of triads
  std::vector<SdfRay> buf(kChunk * 3);
  for (size_t r0 = 0; r0 < rays.size(); r0 += kChunk) {
    size_t n = std::min(kChunk, rays.size() - r0);
    parallelForRange(
        int64_t(n),
        [&](int64_t a, int64_t b) {
          for (int64_t i = a; i < b; ++i)
            makeTriad(rays.ray(r0 + size_t(i)), &drive[(r0 + size_t(i)) * 3], w, options.fluxScale,
                      &buf[size_t(i) * 3]);
        },
        nullptr, 4096);
    size_t m = n * 3;
    if (options.skipZeroFlux)
      m = size_t(std::remove_if(buf.begin(), buf.begin() + std::ptrdiff_t(m), [](const SdfRay& r) { return r.flux == 0.0f; }) -
                 buf.begin());
    writer.write(buf.data(), m);
    if (progress) progress->add(n);
  }
  writer.finish(options.raySetFluxIsSum);
  return writer.count();
}

// ---------------------------------------------------------------- EIA formation

namespace {

class Detector {
 public:
  Detector(const EiLayout& L, const TriadWavelengths& w) : L_(L), w_(w) {
    out_.eia = Image(L.eiaW, L.eiaH, {"R", "G", "B"});
  }
  void bin(const SdfRay& r) {
    // Straight propagation to z = -g; the ray must head toward the detector.
    double z = -L_.gapMm;
    double dz = double(r.n);
    double t = (z - double(r.z)) / dz;
    int channel = -1;
    double lambda = double(r.wavelengthUm) * 1e3;
    for (int c = 0; c < 3; ++c)
      if (std::abs(lambda - w_.nm[size_t(c)]) <= 0.5) channel = c;
    if (channel < 0) {
      ++out_.unknownWavelength;
      return;
    }
    if (!(dz < 0.0) || !(t >= 0.0) || !std::isfinite(t)) {
      ++out_.missed;
      return;
    }
    double x = double(r.x) + t * double(r.l), y = double(r.y) + t * double(r.m);
    double u = x / L_.pixelMm + 0.5 * L_.eiaW, v = 0.5 * L_.eiaH - y / L_.pixelMm;
    if (!(u >= 0.0 && u < L_.eiaW && v >= 0.0 && v < L_.eiaH)) {
      ++out_.missed;
      return;
    }
    out_.eia.at(int(u), int(v), channel) += r.flux;
    ++out_.binned;
  }
  EiaFormation take() { return std::move(out_); }

 private:
  const EiLayout& L_;
  const TriadWavelengths& w_;
  EiaFormation out_;
};

}  // namespace

EiaFormation formEia(const EiLayout& L, const std::vector<SdfRay>& triads, const TriadWavelengths& w) {
  Detector d(L, w);
  for (const SdfRay& r : triads) d.bin(r);
  return d.take();
}

EiaFormation formEiaFromSdf(const EiLayout& L, const std::string& sdfPath, const TriadWavelengths& w,
                            ProgressBar* progress) {
  SdfReader reader(sdfPath);
  Detector d(L, w);
  std::vector<SdfRay> buf(1 << 18);
  for (size_t n; (n = reader.read(buf.data(), buf.size())) > 0;) {
    for (size_t i = 0; i < n; ++i) d.bin(buf[i]);
    if (progress) progress->add(n);
  }
  return d.take();
}

}  // namespace inim
