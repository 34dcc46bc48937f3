#include "core/format.h"
#include "camera/lens_system.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"

namespace inim {

namespace {

constexpr double kTMin = -1e-9;  // sequential tracing: coincident surfaces are still crossed

}  // namespace

const char* traceStatusName(TraceStatus s) {
  switch (s) {
    case TraceStatus::Ok: return "ok";
    case TraceStatus::Missed: return "missed the surface";
    case TraceStatus::Aperture: return "outside the clear aperture";
    case TraceStatus::TotalInternalReflection: return "total internal reflection";
  }
  return "?";
}

double intersectConic(const Vec3d& o, const Vec3d& d, double c, double k, double tMin) {
  if (c == 0.0) {
    if (d.z == 0.0) return -1.0;
    double t = -o.z / d.z;
    return t > tMin ? t : -1.0;
  }
  const double kk = 1.0 + k;
  // F(p) = c (x^2 + y^2 + (1+k) z^2) - 2 z = 0;  A t^2 + 2 b t + C = 0.
  const double A = c * (d.x * d.x + d.y * d.y + kk * d.z * d.z);
  const double b = c * (o.x * d.x + o.y * d.y + kk * o.z * d.z) - d.z;
  const double C = c * (o.x * o.x + o.y * o.y + kk * o.z * o.z) - 2.0 * o.z;
  const double disc = b * b - A * C;
  if (disc < 0.0) return -1.0;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double roots[2] = {-1.0, -1.0};
  if (q != 0.0) {
    roots[0] = C / q;
    if (A != 0.0) roots[1] = q / A;
  } else if (A != 0.0) {
    roots[0] = 0.0;  // b = 0 and disc = 0: a double root at t = 0 only if C = 0
    if (C != 0.0) return -1.0;
  }
  double best = -1.0;
  for (double t : roots) {
    if (!std::isfinite(t) || !(t > tMin)) continue;
    // The sag branch through the vertex has 1 - (1+k) c z >= 0.
    double z = o.z + t * d.z;
    if (1.0 - kk * c * z < -1e-12) continue;
    if (best < 0.0 || t < best) best = t;
  }
  return best;
}

Vec3d conicNormal(const Vec3d& p, double c, double k) {
  Vec3d n(c * p.x, c * p.y, c * (1.0 + k) * p.z - 1.0);
  return glm::normalize(n);
}

bool snellRefract(const Vec3d& d, const Vec3d& nIn, double n1, double n2, Vec3d& out) {
  Vec3d n = glm::dot(d, nIn) > 0.0 ? -nIn : nIn;
  const double eta = n1 / n2;
  const double cosI = std::min(1.0, -glm::dot(n, d));
  const double sin2T = eta * eta * std::max(0.0, 1.0 - cosI * cosI);
  if (sin2T > 1.0) return false;
  const double cosT = std::sqrt(1.0 - sin2T);
  out = glm::normalize(eta * d + (eta * cosI - cosT) * n);
  return true;
}

double fresnelTransmittance(double cosI, double n1, double n2) {
  cosI = std::clamp(std::abs(cosI), 0.0, 1.0);
  const double sin2T = (n1 / n2) * (n1 / n2) * (1.0 - cosI * cosI);
  if (sin2T >= 1.0) return 0.0;
  const double cosT = std::sqrt(1.0 - sin2T);
  const double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  const double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
  return 1.0 - 0.5 * (rs * rs + rp * rp);
}

LensSystem::LensSystem(std::vector<LensSurface> surfaces, std::string name, std::string file)
    : surfaces_(std::move(surfaces)), name_(std::move(name)), file_(std::move(file)) {
  rebuild();
  designStopDiameter_ = stopDiameterMm();
  if (!surfaces_.empty()) sensorDistance_ = surfaces_.back().thicknessMm;
}

void LensSystem::rebuild() {
  z_.assign(surfaces_.size(), 0.0);
  curvature_.resize(surfaces_.size());
  for (size_t i = 0; i < surfaces_.size(); ++i) curvature_[i] = surfaces_[i].curvature();
  stop_ = -1;
  for (size_t i = 0; i < surfaces_.size(); ++i) {
    if (i > 0) z_[i] = z_[i - 1] + surfaces_[i - 1].thicknessMm;
    if (surfaces_[i].isStop && stop_ < 0) stop_ = int(i);
  }
  if (z_.empty()) z_.push_back(0.0);
}

double LensSystem::sag(int i, double r) const {
  return surfaces_[size_t(i)].shape().sag(r * r);
}

double LensSystem::indexAfter(int i, double lambdaNm) const {
  const LensSurface& s = surfaces_[size_t(i)];
  return s.medium ? double(s.medium->n(float(lambdaNm))) : 1.0;
}

std::vector<double> LensSystem::indicesAt(double lambdaNm) const {
  std::vector<double> n(surfaces_.size());
  for (size_t i = 0; i < surfaces_.size(); ++i) n[i] = indexAfter(int(i), lambdaNm);
  return n;
}

bool LensSystem::isDispersive() const {
  for (const auto& s : surfaces_)
    if (s.medium && s.medium->isDispersive()) return true;
  return false;
}

double LensSystem::stopDiameterMm() const {
  return stop_ >= 0 ? surfaces_[size_t(stop_)].apertureMm : 0.0;
}

void LensSystem::setStopDiameterMm(double d) {
  if (stop_ >= 0) surfaces_[size_t(stop_)].apertureMm = d;
}

TraceResult LensSystem::trace(LensRay& r, double lambdaNm, TraceDirection dir,
                              const TraceOptions& opt, std::vector<SurfaceHit>* path) const {
  double nAfter[64];
  std::vector<double> big;
  const double* n = nAfter;
  if (surfaces_.size() <= 64) {
    for (size_t i = 0; i < surfaces_.size(); ++i) nAfter[i] = indexAfter(int(i), lambdaNm);
  } else {
    big = indicesAt(lambdaNm);
    n = big.data();
  }
  return traceWithIndices(r, n, dir, opt, path);
}

TraceResult LensSystem::traceWithIndices(LensRay& r, const double* nAfter, TraceDirection dir,
                                         const TraceOptions& opt, std::vector<SurfaceHit>* path) const {
  TraceResult res;
  const int n = int(surfaces_.size());
  const bool forward = dir == TraceDirection::ObjectToImage;
  const int first = std::max(0, opt.first);
  const int last = opt.last < 0 ? n - 1 : std::min(opt.last, n - 1);
  for (int step = 0; step <= last - first; ++step) {
    const int i = forward ? first + step : last - step;
    const LensSurface& s = surfaces_[size_t(i)];
    const double c = curvature_[size_t(i)];
    const Vec3d oLocal(r.o.x, r.o.y, r.o.z - z_[size_t(i)]);
    double asphereSlope = 0.0;
    const double t = s.isAsphere() ? intersectEvenAsphere(oLocal, r.d, {c, s.conic, &s.asphere}, kTMin, nullptr, &asphereSlope)
                                   : intersectConic(oLocal, r.d, c, s.conic, kTMin);
    if (t < kTMin) {
      res.status = TraceStatus::Missed;
      res.surface = i;
      return res;
    }
    const Vec3d pLocal = oLocal + t * r.d;
    if (opt.apertures) {
      const double r2 = pLocal.x * pLocal.x + pLocal.y * pLocal.y;
      const double semi = s.semiAperture();
      if (r2 > semi * semi) {
        res.status = TraceStatus::Aperture;
        res.surface = i;
        return res;
      }
    }
    const Point3d p(pLocal.x, pLocal.y, pLocal.z + z_[size_t(i)]);
    const double nBefore = i == 0 ? 1.0 : nAfter[i - 1];
    const double n1 = forward ? nBefore : nAfter[i];
    const double n2 = forward ? nAfter[i] : nBefore;
    Vec3d dOut = r.d;
    Vec3d normal(0.0, 0.0, -1.0);
    if (!s.isStop && n1 != n2) {
      normal = s.isAsphere() ? evenAsphereNormalFromSlope(pLocal, asphereSlope) : conicNormal(pLocal, c, s.conic);
      if (glm::dot(normal, r.d) > 0.0) normal = -normal;
      if (!snellRefract(r.d, normal, n1, n2, dOut)) {
        res.status = TraceStatus::TotalInternalReflection;
        res.surface = i;
        return res;
      }
      if (opt.fresnel) res.transmittance *= fresnelTransmittance(-glm::dot(normal, r.d), n1, n2);
    } else if (glm::dot(normal, r.d) > 0.0) {
      normal = -normal;
    }
    if (path) path->push_back({i, p, normal, r.d, dOut, n1, n2});
    r.o = p;
    r.d = dOut;
  }
  return res;
}

void LensSystem::fail(int i, const std::string& column, const std::string& value,
                      const std::string& expected) const {
  std::string key;
  if (i < 0 || i >= int(surfaces_.size())) {
    key = column;
  } else {
    const std::string& src = surfaces_[size_t(i)].source;
    const bool json = src.rfind("surfaces[", 0) == 0;
    if (json) {
      std::string jsonKey = column == "radius"      ? "radius_mm"
                            : column == "thickness" ? "thickness_mm"
                            : column == "aperture"  ? "aperture_mm"
                            : column == "index"     ? "glass"
                                                    : column;
      key = src + "." + jsonKey;
    } else if (src.rfind("SURF ", 0) == 0) {  // a .zmx file: its keywords
      key = src + ", " + (column == "radius"      ? "CURV"
                          : column == "thickness" ? "DISZ"
                          : column == "aperture"  ? "DIAM"
                          : column == "index"     ? "GLAS"
                          : column == "conic"     ? "CONI"
                          : column == "asphere"   ? "PARM"
                                                  : column);
    } else {
      key = (src.empty() ? "surface " + std::to_string(i) : src) + ", column '" + column + "'";
    }
  }
  throw InputError(file_, key, value, expected);
}

void LensSystem::validate() const {
  validateSurfaces();
  validateSpacing();
  const double h = validateNearAxisRay();
  validateStopFill(h);
}

// One stop; each surface's aperture, radius, conic and thickness usable on their own.
void LensSystem::validateSurfaces() const {
  const int n = int(surfaces_.size());
  if (n == 0) throw InputError(file_, "surfaces", "(none)", "at least one surface");
  int stops = 0;
  for (int i = 0; i < n; ++i) stops += surfaces_[size_t(i)].isStop ? 1 : 0;
  if (stops != 1)
    fail(stops > 1 ? n - 1 : -1, "stop", std::to_string(stops) + " aperture stops",
         "exactly one aperture stop (pbrt: a row with radius 0 and index 0; JSON: \"stop\": true)");
  for (int i = 0; i < n; ++i) {
    const LensSurface& s = surfaces_[size_t(i)];
    if (!std::isfinite(s.apertureMm) || !(s.apertureMm > 0.0))
      fail(i, "aperture", formatNumber(s.apertureMm), "a clear aperture diameter > 0 mm");
    if (!std::isfinite(s.radiusMm)) fail(i, "radius", formatNumber(s.radiusMm), "a finite radius (0 = flat)");
    if (!std::isfinite(s.conic)) fail(i, "conic", formatNumber(s.conic), "a finite conic constant");
    if (!std::isfinite(s.thicknessMm) || s.thicknessMm < 0.0)
      fail(i, "thickness", formatNumber(s.thicknessMm), "a thickness >= 0 mm (vertices in order along the axis)");
    if (i + 1 < n && !s.isAir() && s.thicknessMm <= 0.0)
      fail(i, "thickness", formatNumber(s.thicknessMm), "a glass thickness > 0 mm");
    if (i == n - 1 && !s.isAir())
      fail(i, "index", s.mediumName, "air after the last surface (image space)");
    if (s.isStop && s.radiusMm != 0.0) fail(i, "radius", formatNumber(s.radiusMm), "a flat stop (radius 0)");
    validateAsphere(i);
    const double c = s.curvature();
    if (c != 0.0) {
      const double a = s.semiAperture();
      if (1.0 - (1.0 + s.conic) * c * c * a * a < 0.0) {
        std::string what = s.conic == 0.0 ? "|radius| >= aperture/2 = " + formatNumber(a) + " mm (a sphere of radius " +
                                                formatNumber(std::abs(s.radiusMm)) + " mm cannot have this aperture)"
                                          : "a conic surface defined over the whole aperture (1 - (1+k) c^2 (D/2)^2 >= 0)";
        fail(i, "aperture", formatNumber(s.apertureMm), what);
      }
    }
  }
}

// Aspheric terms: finite, not on the stop, and a sag and slope defined over the whole aperture
// (a conic term can end inside it), sampled finely enough to find where it ends.
void LensSystem::validateAsphere(int i) const {
  const LensSurface& s = surfaces_[size_t(i)];
  if (!s.isAsphere()) return;
  for (size_t j = 0; j < s.asphere.size(); ++j)
    if (!std::isfinite(s.asphere[j]))
      fail(i, "asphere", formatNumber(s.asphere[j]), "finite even-asphere coefficients (term " + std::to_string(j + 1) + ")");
  if (s.isStop) fail(i, "asphere", formatNumber(s.asphere[0]), "a flat stop (no aspheric terms)");
  const EvenAsphere shape = s.shape();
  constexpr int kSamples = 256;
  for (int j = 0; j <= kSamples; ++j) {
    const double r = s.semiAperture() * j / kSamples;
    if (!std::isfinite(shape.sag(r * r)) || !std::isfinite(shape.slope(r * r)))
      fail(i, "aperture", formatNumber(s.apertureMm),
           "an aperture within which the aspheric sag is defined (it ends at height " + formatNumber(r) + " mm)");
  }
}

// Neighbouring surfaces must not cross inside their common aperture. Aspheres can cross inside
// it without crossing at its edge, so heights are sampled.
void LensSystem::validateSpacing() const {
  const int n = int(surfaces_.size());
  for (int i = 0; i + 1 < n; ++i) {
    const double rMax = std::min(surfaces_[size_t(i)].semiAperture(), surfaces_[size_t(i + 1)].semiAperture());
    const bool sampled = surfaces_[size_t(i)].isAsphere() || surfaces_[size_t(i + 1)].isAsphere();
    const int samples = sampled ? 64 : 1;
    for (int j = 1; j <= samples; ++j) {
      const double r = rMax * j / samples;
      const double zi = z_[size_t(i)] + sag(i, r);
      const double zj = z_[size_t(i + 1)] + sag(i + 1, r);
      if (zi > zj + 1e-9)
        fail(i, "thickness", formatNumber(surfaces_[size_t(i)].thicknessMm),
             "a thickness large enough that this surface and the next do not cross within their apertures "
             "(they cross by " + formatNumber(zi - zj) + " mm at height " + formatNumber(r) + " mm)");
    }
  }
}

// A near-axis ray from an object at infinity must pass; returns its height.
double LensSystem::validateNearAxisRay() const {
  double minSemi = std::numeric_limits<double>::infinity();
  for (const auto& s : surfaces_) minSemi = std::min(minSemi, s.semiAperture());
  const double h = 1e-3 * minSemi;
  LensRay ray{{0.0, h, -1.0}, {0.0, 0.0, 1.0}};
  TraceResult tr = trace(ray, kLensReferenceLambdaNm, TraceDirection::ObjectToImage);
  if (!tr.ok())
    fail(tr.surface, tr.status == TraceStatus::Aperture ? "aperture" : "radius",
         tr.status == TraceStatus::Aperture ? formatNumber(surfaces_[size_t(tr.surface)].apertureMm)
                                            : formatNumber(surfaces_[size_t(tr.surface)].radiusMm),
         std::string("a lens that passes near-axis rays (a ray at height ") + formatNumber(h) + " mm is blocked here: " +
             traceStatusName(tr.status) + ")");
  return h;
}

// The axial beam from infinity must be able to fill the stop: find the entrance height whose ray
// reaches the stop edge (apertures off; from the near-axis height h), then check every other
// aperture on it.
void LensSystem::validateStopFill(double h) const {
  const double rStop = surfaces_[size_t(stop_)].semiAperture();
  auto stopHeight = [&](double hIn, bool& ok) {
    LensRay rr{{0.0, hIn, -1.0}, {0.0, 0.0, 1.0}};
    std::vector<SurfaceHit> path;
    TraceOptions o;
    o.apertures = false;
    TraceResult res = trace(rr, kLensReferenceLambdaNm, TraceDirection::ObjectToImage, o, &path);
    ok = res.ok() || res.surface > stop_;
    for (const auto& hit : path)
      if (hit.surface == stop_) return hit.p.y;
    ok = false;
    return 0.0;
  };
  bool ok = true;
  const double yStopSmall = stopHeight(h, ok);
  if (!ok || yStopSmall <= 0.0) return;  // no real marginal ray to check (diverging front group)
  const double target = rStop * (1.0 - 1e-6);
  double hi = h * target / yStopSmall;  // paraxial guess, refined by secant steps
  for (int it = 0; it < 40; ++it) {
    bool okH = true;
    double y = stopHeight(hi, okH);
    if (!okH) break;
    if (std::abs(y - target) < 1e-12 * rStop) break;
    double hPrev = hi * 0.999;
    bool okP = true;
    double yPrev = stopHeight(hPrev, okP);
    if (!okP || y == yPrev) break;
    hi = hi + (target - y) * (hi - hPrev) / (y - yPrev);
  }
  // Fraction of the stop radius the axial beam reaches before another aperture clips it.
  // Real prescriptions round their clear apertures (dgauss.50mm: 99.3 %); a stop the beam
  // fills to less than 90 % is larger than its neighbouring elements allow.
  constexpr double kMinFill = 0.9;
  LensRay marg{{0.0, hi * kMinFill, -1.0}, {0.0, 0.0, 1.0}};
  TraceResult mr = trace(marg, kLensReferenceLambdaNm, TraceDirection::ObjectToImage);
  if (!mr.ok() && mr.surface != stop_) {
    double lo = 0.0, up = kMinFill;
    for (int it = 0; it < 40; ++it) {
      const double f = 0.5 * (lo + up);
      LensRay m2{{0.0, hi * f, -1.0}, {0.0, 0.0, 1.0}};
      (trace(m2, kLensReferenceLambdaNm, TraceDirection::ObjectToImage).ok() ? lo : up) = f;
    }
    fail(stop_, "aperture", formatNumber(surfaces_[size_t(stop_)].apertureMm),
         "a stop the axial beam can fill: surface " + std::to_string(mr.surface) + " (" +
             (surfaces_[size_t(mr.surface)].source.empty() ? "" : surfaces_[size_t(mr.surface)].source + ", ") +
             "aperture " + formatNumber(surfaces_[size_t(mr.surface)].apertureMm) + " mm, " + traceStatusName(mr.status) +
             ") limits the axial beam to " + formatNumber(100.0 * lo) +
             " % of the stop radius (apertures inconsistent: the stop is larger than its neighbours allow)");
  }
}

}  // namespace inim
