#include "display_view/estimators/lenslet_map.h"

#include <algorithm>
#include <cstring>

namespace inim {

MlaLanding::MlaLanding(const EstimatorContext& context, uint64_t& rays)
    : context_(context),
      mode_(context.mla.fresnelMode() == FresnelMode::Stochastic ? FresnelMode::Weighted : context.mla.fresnelMode()),
      rays_(rays) {}

bool MlaLanding::land(const Vec2d& crossing, const Vec2d& slope, float lambdaNm, Landing& out) const {
  ++rays_;
  const float frontZ = context_.frontZ;
  const Vec3 d = glm::normalize(Vec3(float(slope.x), float(slope.y), -1.0f));
  const Point3 o = Point3(float(crossing.x), float(crossing.y), frontZ) + 1e-3f * (-d);
  if (!(d.z < 0.0f) || !(o.z > frontZ)) return false;
  const Point3 p = o + ((frontZ - o.z) / d.z) * d;
  if (!context_.area.contains(p.x, p.y)) return false;
  PanelArrival arrival;
  if (!context_.mla.traceToPanel(Ray{p, d, 0.0f, kInfinity}, lambdaNm, mode_, nullptr, arrival)) return false;
  if (!context_.panel.emissionPointPx(arrival.p, arrival.d, lambdaNm, out.uv, out.factor)) return false;
  out.throughput = arrival.throughput;
  out.k = arrival.lensletK;
  out.l = arrival.lensletL;
  return true;
}

// Central differences at the table's rms spread (then a quarter of it), every probe landing
// through the reference ray's lenslet; one-sided toward the side that does where only one does.
bool LensletMapCache::measure(const Vec2d& crossing, const Vec2d& slope, const ApertureTable& table,
                              LensletMap& out) const {
  const float lambdaNm = lambdaNm_;
  Landing centre;
  if (!mla_.land(crossing, slope, lambdaNm, centre)) return false;
  out.k = centre.k;
  out.l = centre.l;
  out.ok = false;
  double A[2][2], B[2][2];
  for (double f : {1.0, 0.25}) {
    const double stepCrossing = f * std::max(table.rmsH, 0.002), stepSlope = f * std::max(table.rmsS, 1e-4);
    bool good = true;
    for (int m = 0; m < 4 && good; ++m) {
      const int axis = m & 1;
      const bool bySlope = m >= 2;
      const double e = bySlope ? stepSlope : stepCrossing;
      const Vec2d dv = axis == 0 ? Vec2d(e, 0.0) : Vec2d(0.0, e);
      Landing plus, minus;
      const bool okP = bySlope ? mla_.land(crossing, slope + dv, lambdaNm, plus)
                               : mla_.land(crossing + dv, slope, lambdaNm, plus);
      const bool okM = bySlope ? mla_.land(crossing, slope - dv, lambdaNm, minus)
                               : mla_.land(crossing - dv, slope, lambdaNm, minus);
      const bool inP = okP && plus.sameLenslet(centre), inM = okM && minus.sameLenslet(centre);
      if (!inP && !inM) {
        good = false;
        break;
      }
      const Vec2d up = inP ? plus.uv : centre.uv, um = inM ? minus.uv : centre.uv;
      const double span = (inP ? e : 0.0) + (inM ? e : 0.0);
      double(&M)[2][2] = bySlope ? B : A;
      M[0][axis] = (up.x - um.x) / span;
      M[1][axis] = (up.y - um.y) / span;
    }
    if (good) {
      out.ok = true;
      break;
    }
  }
  if (!out.ok) return true;
  std::memcpy(out.A, A, sizeof A);
  std::memcpy(out.B, B, sizeof B);
  out.offsets.resize(2 * table.points.size());
  for (size_t i = 0; i < table.points.size(); ++i) {
    const auto& q = table.points[i];
    out.offsets[2 * i] = float(A[0][0] * q.dhx + A[0][1] * q.dhy + B[0][0] * q.dsx + B[0][1] * q.dsy);
    out.offsets[2 * i + 1] = float(A[1][0] * q.dhx + A[1][1] * q.dhy + B[1][0] * q.dsx + B[1][1] * q.dsy);
  }
  return true;
}

const LensletMap* LensletMapCache::find(size_t block, const ApertureTable& table, const Vec2d& crossing,
                                        const Vec2d& slope, const Landing& landing) {
  Entry* entry = nullptr;
  for (auto& e : entries_)
    if (e.block == block && e.k == landing.k && e.l == landing.l) entry = &e;
  if (!entry) {
    entries_.push_back({block, landing.k, landing.l, {}});
    entry = &entries_.back();
  }
  if (!entry->map.ok) {
    LensletMap m;
    if (measure(crossing, slope, table, m) && m.ok && m.k == landing.k && m.l == landing.l)
      entry->map = std::move(m);
  }
  return entry->map.ok ? &entry->map : nullptr;
}

}  // namespace inim
