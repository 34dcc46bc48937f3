#include "mla_optics/real_lens_rays.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/settings_table.h"
#include "core/parallel.h"
#include "core/progress.h"

namespace inim {

const char* realLensRayModelName(RealLensRayModel m) {
  return m == RealLensRayModel::Centroid ? "centroid" : "chief";
}

RealLensRayModel parseRealLensRayModel(const std::string& text, const std::string& key) {
  if (text == "centroid") return RealLensRayModel::Centroid;
  if (text == "chief") return RealLensRayModel::Chief;
  throw InputError("", key, "\"" + text + "\"", "centroid (the exit bundle's power centroid) or chief (the ray through "
                                                  "the lenslet's aperture centre)");
}

std::string summaryText(const RealLensRayOptions& o, const RealLensRayStats& st) {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "real-lens rays (%s, %.6g nm): %llu rays in %.2f s; angle to the pinhole rays through the lens "
                "centres: max %.4g deg, mean %.4g deg; %llu fell back to the pinhole ray, %llu crosstalk",
                realLensRayModelName(o.model), o.wavelengthNm, (unsigned long long)st.rays, st.seconds,
                st.maxDeviationDeg, st.meanDeviationDeg, (unsigned long long)st.fallback,
                (unsigned long long)st.crosstalk);
  return buf;
}

Vec3d aimAt(const RealMla& mla, const Point3d& pixel, const Point3d& q, double lambdaNm) {
  const double zf = mla.flatZ();
  const bool throughFlat =
      mla.geometry().orientation == Mla::Orientation::CurvedTowardViewer && q.z > zf && pixel.z < zf;
  const double rx = q.x - pixel.x, ry = q.y - pixel.y;
  const double rho = std::sqrt(rx * rx + ry * ry);
  if (!throughFlat || rho == 0.0) {
    Vec3d d = q - pixel;
    return d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  }
  // Air height A to the flat face, glass height B above it; find tau = tan(theta_air) with
  // A tau + B tan(theta_glass(tau)) = rho (monotonic): safeguarded Newton on [0, rho / A].
  const double A = zf - pixel.z, B = q.z - zf, n = mla.n(lambdaNm);
  double lo = 0.0, hi = rho / A, tau = rho / (A + B / n);
  for (int it = 0; it < 60; ++it) {
    const double c = std::sqrt(1.0 + tau * tau);
    const double sg = tau / (n * c);
    const double cg2 = 1.0 - sg * sg;
    const double tg = sg / std::sqrt(cg2);
    const double F = A * tau + B * tg - rho;
    if (F > 0.0) hi = tau;
    else lo = tau;
    const double dF = A + B / (cg2 * std::sqrt(cg2)) / (n * c * c * c);
    double next = tau - F / dF;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - tau) <= 1e-15 * (1.0 + tau)) {
      tau = next;
      break;
    }
    tau = next;
  }
  const double c = std::sqrt(1.0 + tau * tau);
  return Vec3d(rx / rho * tau / c, ry / rho * tau / c, 1.0 / c);
}

namespace {

bool chiefRay(const RealMla& mla, const Point3d& pixel, int k, int l, double lambdaNm, RealLensRay& out) {
  const Point3d c = mla.lensletCentre(k, l);
  const Point3d v(c.x, c.y, mla.vertexZ());
  MlaExit ex;
  if (!mla.trace(pixel, aimAt(mla, pixel, v, lambdaNm), lambdaNm, FresnelMode::Off, nullptr, ex) || !(ex.d.z > 0.0))
    return false;
  out.d = ex.d;
  out.o = ex.p - (ex.p.z / ex.d.z) * ex.d;
  out.o.z = 0.0;
  out.exitK = ex.capK;
  out.exitL = ex.capL;
  out.real = true;
  return true;
}

// The exit bundle of the pixel through lenslet (k, l), parameterised by the point Q where each
// ray crosses the cap (inside the clear aperture A): a midpoint grid over A's bounding box,
// points outside A skipped. Each ray's weight is the Lambertian intensity (cos theta) times the
// solid angle its grid cell subtends at the pixel (d Omega / dA from central differences of the
// aim direction) times its Fresnel transmittance.
bool centroidRay(const RealMla& mla, const Point3d& pixel, int k, int l, const RealLensRayOptions& o,
                 RealLensRay& out) {
  const Point3d c = mla.lensletCentre(k, l);
  double rx = 0.0, ry = 0.0;
  for (const auto& p : mla.apertureOutline()) rx = std::max(rx, std::abs(p[0])), ry = std::max(ry, std::abs(p[1]));
  const int N = std::max(1, o.samplesPerAxis);
  const double hx = 2.0 * rx / N, hy = 2.0 * ry / N;
  const double e = 1e-5 * std::max(rx, ry);  // finite-difference step on the cap
  auto aim = [&](double lx, double ly) {
    return aimAt(mla, pixel, Point3d(c.x + lx, c.y + ly, mla.capZ(lx, ly)), o.wavelengthNm);
  };
  double W = 0.0;
  Vec3d sumD(0.0), sumO(0.0);
  int used = 0;
  for (int j = 0; j < N; ++j) {
    const double ly = -ry + (j + 0.5) * hy;
    for (int i = 0; i < N; ++i) {
      const double lx = -rx + (i + 0.5) * hx;
      if (!mla.inClearAperture(lx, ly)) continue;
      const Vec3d w = aim(lx, ly);
      const Vec3d ax = aim(lx + e, ly) - aim(lx - e, ly), ay = aim(lx, ly + e) - aim(lx, ly - e);
      const Vec3d cr(ax.y * ay.z - ax.z * ay.y, ax.z * ay.x - ax.x * ay.z, ax.x * ay.y - ax.y * ay.x);
      const double dOmega = std::sqrt(cr.x * cr.x + cr.y * cr.y + cr.z * cr.z) / (4.0 * e * e);
      MlaExit ex;
      if (!mla.trace(pixel, w, o.wavelengthNm, FresnelMode::Weighted, nullptr, ex)) continue;
      if (!(ex.d.z > 0.0) || ex.capK != k || ex.capL != l) continue;
      const double wt = w.z * dOmega * ex.throughput;
      if (!(wt > 0.0) || !std::isfinite(wt)) continue;
      W += wt;
      sumD += wt * ex.d;
      sumO += wt * (ex.p - (ex.p.z / ex.d.z) * ex.d);
      ++used;
    }
  }
  if (!(W > 0.0)) return false;
  const double len = std::sqrt(sumD.x * sumD.x + sumD.y * sumD.y + sumD.z * sumD.z);
  if (!(len > 0.0)) return false;
  out.d = sumD / len;
  out.o = sumO / W;
  out.o.z = 0.0;
  out.exitK = k, out.exitL = l;
  out.samplesUsed = used;
  out.real = true;
  return true;
}

// Real-lens rays as a function of the pixel's offset (dx, dy) = pixel - lens centre, on a grid
// symmetric about 0, from lenslet (k0, l0). Entries whose ray left through another lenslet
// (crosstalk) are marked unusable, so those pixels are traced directly. Stores the correction of tan(theta) to the pinhole
// ray's (-dx / g, -dy / g) and the origin's offset from the lens centre.
class OffsetTable {
 public:
  OffsetTable(const RealMla& mla, const RealLensRayOptions& o, double maxDx, double maxDy, double h)
      : h_(h), g_(-mla.panelZ()) {
    nx_ = int(std::ceil(maxDx / h)) + 1;
    ny_ = int(std::ceil(maxDy / h)) + 1;
    const int k0 = mla.geometry().cols / 2, l0 = mla.geometry().rows / 2;
    const Point3d c = mla.lensletCentre(k0, l0);
    const size_t n = size_t(nx_ + 1) * size_t(ny_ + 1);
    e_.resize(n);
    // One quadrant (dx, dy >= 0); the lattice and the apertures are symmetric under x -> -x
    // and y -> -y about a lens centre.
    parallelForRange(
        int64_t(n),
        [&](int64_t a, int64_t b) {
          for (int64_t idx = a; idx < b; ++idx) {
            const int i = int(idx % (nx_ + 1)), j = int(idx / (nx_ + 1));
            const double dx = i * h_, dy = j * h_;
            RealLensRay r;
            Entry& e = e_[size_t(idx)];
            const Point3d pixel(c.x + dx, c.y + dy, mla.panelZ());
            e.ok = (o.model == RealLensRayModel::Centroid ? centroidRay(mla, pixel, k0, l0, o, r)
                                                          : chiefRay(mla, pixel, k0, l0, o.wavelengthNm, r)) &&
                   r.d.z > 0.0 && r.exitK == k0 && r.exitL == l0;
            if (!e.ok) continue;
            e.tx = r.d.x / r.d.z + dx / g_;
            e.ty = r.d.y / r.d.z + dy / g_;
            e.ox = r.o.x - c.x;
            e.oy = r.o.y - c.y;
          }
        },
        nullptr, 8);
  }
  // False when (dx, dy) is outside the table or next to an entry without a ray.
  bool lookup(double dx, double dy, RealLensRay& r) const {
    const double sx = dx < 0.0 ? -1.0 : 1.0, sy = dy < 0.0 ? -1.0 : 1.0;
    const double u = std::abs(dx) / h_, v = std::abs(dy) / h_;
    const int i = int(u), j = int(v);
    if (i >= nx_ || j >= ny_) return false;
    const double fu = u - i, fv = v - j;
    const Entry& a = at(i, j);
    const Entry& b = at(i + 1, j);
    const Entry& c = at(i, j + 1);
    const Entry& d = at(i + 1, j + 1);
    if (!(a.ok && b.ok && c.ok && d.ok)) return false;
    auto mix = [&](double Entry::*m) {
      return (1 - fv) * ((1 - fu) * a.*m + fu * b.*m) + fv * ((1 - fu) * c.*m + fu * d.*m);
    };
    const double tx = -dx / g_ + sx * mix(&Entry::tx), ty = -dy / g_ + sy * mix(&Entry::ty);
    const double inv = 1.0 / std::sqrt(1.0 + tx * tx + ty * ty);
    r.d = Vec3d(tx * inv, ty * inv, inv);
    r.o = Vec3d(sx * mix(&Entry::ox), sy * mix(&Entry::oy), 0.0);  // relative to the lens centre
    r.real = true;
    return true;
  }

 private:
  struct Entry {
    double tx = 0, ty = 0, ox = 0, oy = 0;
    bool ok = false;
  };
  const Entry& at(int i, int j) const { return e_[size_t(j) * size_t(nx_ + 1) + size_t(i)]; }
  double h_, g_;
  int nx_ = 0, ny_ = 0;
  std::vector<Entry> e_;
};

}  // namespace

RealLensRay realLensRay(const RealMla& mla, const Point3d& pixel, int k, int l, const RealLensRayOptions& o) {
  RealLensRay r;
  bool ok = o.model == RealLensRayModel::Centroid ? centroidRay(mla, pixel, k, l, o, r) : false;
  if (!ok) ok = chiefRay(mla, pixel, k, l, o.wavelengthNm, r);
  if (!ok || !(r.d.z > 0.0)) {
    const Point3d c = mla.lensletCentre(k, l);
    Vec3d d = c - pixel;
    r = RealLensRay{};
    r.o = c;
    r.d = d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    r.real = false;
  }
  return r;
}

RaySet generateRealLensRays(const EiLayout& L, const RealMla& mla, const RealLensRayOptions& o,
                            RealLensRayStats* stats, ProgressBar* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::abs(mla.geometry().gapMm - L.gapMm) > 1e-9 * std::max(1.0, L.gapMm))
    throw InputError("", "gap", std::to_string(L.gapMm) + " mm (layout) vs " + std::to_string(mla.geometry().gapMm) +
                                    " mm (MLA)",
                     "the same panel gap for the layout and the real MLA");
  if (!(o.wavelengthNm >= 300.0 && o.wavelengthNm <= 1000.0))
    throw InputError("", "--wavelength-nm", std::to_string(o.wavelengthNm), "a wavelength in 300-1000 nm");
  RaySet rays;
  const size_t N = size_t(L.numRays());
  for (auto* v : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) v->resize(N);
  const int n = L.eiW, m = L.eiH;
  const double g = L.gapMm;
  // Rays from a table of pixel offsets (see RealLensRayOptions::tableStepMm).
  std::unique_ptr<OffsetTable> table;
  if (o.tableStepMm > 0.0) {
    double maxDx = 0.0, maxDy = 0.0;
    // Box corners of every EI (all lattices): a bound on every pixel's offset from its lens.
    for (int k = 0; k < L.eiCols; ++k)
      for (int l = 0; l < L.eiRows; ++l) {
        if (!L.isHex() && l > 0 && k > 0) break;  // separable: row 0 and column 0 suffice
        const Point3d c = mla.lensletCentre(k, l);
        const int c0 = L.eiBoxCol0(k, l), r0 = L.eiBoxRow0(k, l);
        for (int i : {0, n - 1}) maxDx = std::max(maxDx, std::abs(L.pixelCentreX(c0 + i) - c.x));
        for (int j : {0, m - 1}) maxDy = std::max(maxDy, std::abs(L.pixelCentreY(r0 + j) - c.y));
      }
    table = std::make_unique<OffsetTable>(mla, o, maxDx + o.tableStepMm, maxDy + o.tableStepMm, o.tableStepMm);
  }
  std::mutex statsMutex;
  RealLensRayStats st;
  double sumDev = 0.0;
  parallelForRange(
      L.numEis(),
      [&](int64_t e0, int64_t e1) {
        uint64_t fallback = 0, crosstalk = 0;
        double maxDev = 0.0, devSum = 0.0;
        for (int64_t e = e0; e < e1; ++e) {
          const int k = int(e / L.eiRows);
          const int l = L.eiRows - 1 - int(e % L.eiRows);
          const Point3d c = mla.lensletCentre(k, l);
          L.forEachRayOfEi(k, l, [&](int64_t ri, int col, int row, int, int) {
              const size_t r = size_t(ri);
              const Point3d pixel(L.pixelCentreX(col), L.pixelCentreY(row), -g);
              RealLensRay rr;
              if (table && table->lookup(pixel.x - c.x, pixel.y - c.y, rr)) {
                rr.o += Vec3d(c.x, c.y, 0.0);
                rr.exitK = k, rr.exitL = l;
              } else {
                rr = realLensRay(mla, pixel, k, l, o);
              }
              rays.set(r, Vec3(rr.o), Vec3(rr.d));
              if (!rr.real) ++fallback;
              if (o.model == RealLensRayModel::Chief && rr.real && (rr.exitK != k || rr.exitL != l)) ++crosstalk;
              Vec3d pd = c - pixel;
              pd /= std::sqrt(pd.x * pd.x + pd.y * pd.y + pd.z * pd.z);
              const double cosA = std::clamp(pd.x * rr.d.x + pd.y * rr.d.y + pd.z * rr.d.z, -1.0, 1.0);
              // acos loses precision near 1: use the cross product's length.
              const Vec3d x(pd.y * rr.d.z - pd.z * rr.d.y, pd.z * rr.d.x - pd.x * rr.d.z, pd.x * rr.d.y - pd.y * rr.d.x);
              const double dev = std::atan2(std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z), cosA) * 180.0 / M_PI;
              maxDev = std::max(maxDev, dev);
              devSum += dev;
          });
          if (progress) progress->add(uint64_t(L.eiRayCount(k, l)));
        }
        std::lock_guard<std::mutex> lock(statsMutex);
        st.fallback += fallback;
        st.crosstalk += crosstalk;
        st.maxDeviationDeg = std::max(st.maxDeviationDeg, maxDev);
        sumDev += devSum;
      },
      nullptr, 4);
  if (stats) {
    st.rays = N;
    st.meanDeviationDeg = N ? sumDev / double(N) : 0.0;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *stats = st;
  }
  return rays;
}

std::optional<RealLensRayOptions> resolveRealLens(bool on, const std::optional<std::string>& model,
                                                  const std::optional<double>& wavelengthNm) {
  if (!on && (model || wavelengthNm))
    throw InputError("", model ? "real_lens_ray" : "wavelength_nm",
                     model ? "\"" + *model + "\"" : formatNumber(*wavelengthNm),
                     "--real-lens or --chief-rays traced as well (the pinhole model has no refraction)");
  if (!on) return std::nullopt;
  RealLensRayOptions ro;
  if (model) ro.model = parseRealLensRayModel(*model, "real_lens_ray");
  if (wavelengthNm) checkSettingRange(*findSetting("wavelength_nm"), *wavelengthNm, "", "wavelength_nm");
  if (wavelengthNm) ro.wavelengthNm = *wavelengthNm;
  return ro;
}

}  // namespace inim
