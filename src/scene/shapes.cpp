#include "scene/shapes.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace inim {

using glm::dvec3;

void Shape::setTransform(const Transform& toWorld) {
  const glm::dmat4& m = toWorld.matrix();
  L = glm::dmat3(m);
  T = dvec3(m[3]);
  Linv = glm::inverse(L);
  Nmat = glm::transpose(Linv);
  detL = glm::determinant(L);
  glm::dmat3 g = glm::transpose(L) * L;
  double s2 = (g[0][0] + g[1][1] + g[2][2]) / 3.0;
  similarity = true;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (std::abs(g[c][r] - (c == r ? s2 : 0.0)) > 1e-9 * s2) similarity = false;
  uniformScale = std::sqrt(s2);
}

size_t Shape::finalize() {
  size_t dropped = 0;
  if (type == ShapeType::Mesh) {
    std::vector<uint32_t> kept;
    kept.reserve(indices.size());
    triCdf.clear();
    triN.clear();
    double sum = 0.0;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
      uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
      bool ok = a < P.size() && b < P.size() && c < P.size();
      double ar = 0.0;
      if (ok) {
        dvec3 p0(P[a]), p1(P[b]), p2(P[c]);
        ok = isFinite(P[a]) && isFinite(P[b]) && isFinite(P[c]);
        dvec3 e1 = p1 - p0, e2 = p2 - p0, e3 = p2 - p1;
        ar = 0.5 * glm::length(glm::cross(e1, e2));
        double maxEdge2 = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
        // Zero-area or needle-thin triangles have no well-defined normal: skip them.
        ok = ok && std::isfinite(ar) && ar > 1e-10 * maxEdge2;
      }
      if (!ok) {
        ++dropped;
        continue;
      }
      kept.insert(kept.end(), {a, b, c});
      triN.push_back(Vec3(glm::normalize(glm::cross(dvec3(P[b]) - dvec3(P[a]), dvec3(P[c]) - dvec3(P[a])))));
      sum += ar;
      triCdf.push_back(sum);
    }
    indices.swap(kept);
    area = sum;
    // Two triangles (0,1,2), (0,2,3) of a planar quad: a parallelogram if p3 = p0 + p2 - p1.
    parallelogram = false;
    if (indices.size() == 6 && P.size() == 4 && indices[0] == 0 && indices[1] == 1 &&
        indices[2] == 2 && indices[3] == 0 && indices[4] == 2 && indices[5] == 3) {
      Vec3 d = P[0] + P[2] - P[1] - P[3];
      float scale = glm::length(P[2] - P[0]);
      if (glm::length(d) <= 1e-6f * scale) {
        parallelogram = true;
        corner = P[0];
        e1 = P[1] - P[0];
        e2 = P[3] - P[0];
        pnormal = glm::normalize(glm::cross(e1, e2));
      }
    }
    for (double& c : triCdf) c /= sum > 0.0 ? sum : 1.0;
    lo = Point3(kInfinity);
    hi = Point3(-kInfinity);
    for (uint32_t i : indices) {
      lo = glm::min(lo, P[i]);
      hi = glm::max(hi, P[i]);
    }
  } else {
    const double pi = 3.14159265358979323846;
    double r = radius, h = height;
    dvec3 half;
    switch (type) {
      case ShapeType::Sphere:
        objectArea = 4.0 * pi * r * r;
        for (int i = 0; i < 3; ++i)
          half[i] = r * std::sqrt(L[0][i] * L[0][i] + L[1][i] * L[1][i] + L[2][i] * L[2][i]);
        break;
      case ShapeType::Disk:
        objectArea = pi * r * r;
        for (int i = 0; i < 3; ++i) half[i] = r * std::sqrt(L[0][i] * L[0][i] + L[1][i] * L[1][i]);
        break;
      default:  // cylinder
        objectArea = 2.0 * pi * r * h + (caps ? 2.0 * pi * r * r : 0.0);
        for (int i = 0; i < 3; ++i)
          half[i] = r * std::sqrt(L[0][i] * L[0][i] + L[1][i] * L[1][i]) + 0.5 * h * std::abs(L[2][i]);
        break;
    }
    // World area: exact for similarity transforms, |det|^(2/3) scaling otherwise (only
    // used for light-power estimates; sampling pdfs are exact either way).
    area = objectArea * (similarity ? uniformScale * uniformScale
                                    : std::pow(std::abs(detL), 2.0 / 3.0));
    double pad = 1e-6 * (glm::length(half) + glm::length(T)) + 1e-30;
    lo = Point3(T - half - pad);
    hi = Point3(T + half + pad);
  }
  extent = glm::length(hi - lo);
  return dropped;
}

// ---- Analytic intersections ---------------------------------------------------------------

namespace {
// Roots of a t^2 + b t + c with the discriminant given separately (computed in a
// cancellation-free form by the caller). Returns false if none is real.
inline bool stableRoots(double a, double b, double c, double disc, double* t0, double* t1) {
  if (!(disc >= 0.0) || a == 0.0) return false;
  double rd = std::sqrt(disc);
  double q = (b < 0.0) ? -0.5 * (b - rd) : -0.5 * (b + rd);
  double r0 = q / a;
  double r1 = (q != 0.0) ? c / q : r0;
  if (r0 > r1) std::swap(r0, r1);
  *t0 = r0;
  *t1 = r1;
  return true;
}
}  // namespace

bool intersectSphereLocal(const dvec3& o, const dvec3& d, double r, double tMin, double tMax,
                          double* t) {
  double a = glm::dot(d, d);
  if (!(a > 0.0)) return false;
  double b = 2.0 * glm::dot(o, d);
  double c = glm::dot(o, o) - r * r;
  // Discriminant as 4a (r - |v|)(r + |v|), v = o - (b/2a) d: the distance of the line from
  // the centre. No cancellation for grazing rays (pbrt-v4).
  dvec3 v = o - (b / (2.0 * a)) * d;
  double len = glm::length(v);
  double disc = 4.0 * a * (r + len) * (r - len);
  double t0, t1;
  if (!stableRoots(a, b, c, disc, &t0, &t1)) return false;
  if (t0 > tMin && t0 < tMax) {
    *t = t0;
    return true;
  }
  if (t1 > tMin && t1 < tMax) {
    *t = t1;
    return true;
  }
  return false;
}

bool intersectDiskLocal(const dvec3& o, const dvec3& d, double r, double tMin, double tMax,
                        double* t) {
  if (d.z == 0.0) return false;
  double th = -o.z / d.z;
  if (!(th > tMin && th < tMax)) return false;
  double x = o.x + th * d.x, y = o.y + th * d.y;
  if (x * x + y * y > r * r) return false;
  *t = th;
  return true;
}

bool intersectCylinderLocal(const dvec3& o, const dvec3& d, double r, double h, bool caps,
                            double tMin, double tMax, double* t, int* part) {
  double best = tMax;
  int bestPart = -1;
  double hz = 0.5 * h;
  double a = d.x * d.x + d.y * d.y;
  if (a > 0.0) {
    double bh = o.x * d.x + o.y * d.y;
    double b = 2.0 * bh;
    double c = o.x * o.x + o.y * o.y - r * r;
    double f = bh / a;
    double vx = o.x - f * d.x, vy = o.y - f * d.y;
    double len = std::sqrt(vx * vx + vy * vy);
    double disc = 4.0 * a * (r + len) * (r - len);
    double t0, t1;
    if (stableRoots(a, b, c, disc, &t0, &t1)) {
      for (double tc : {t0, t1}) {
        if (!(tc > tMin && tc < best)) continue;
        double z = o.z + tc * d.z;
        if (z < -hz || z > hz) continue;
        best = tc;
        bestPart = kCylSide;
        break;
      }
    }
  }
  if (caps && d.z != 0.0) {
    for (int s = 0; s < 2; ++s) {
      double zc = s == 0 ? hz : -hz;
      double tc = (zc - o.z) / d.z;
      if (!(tc > tMin && tc < best)) continue;
      double x = o.x + tc * d.x, y = o.y + tc * d.y;
      if (x * x + y * y > r * r) continue;
      best = tc;
      bestPart = s == 0 ? kCylTop : kCylBottom;
    }
  }
  if (bestPart < 0) return false;
  *t = best;
  *part = bestPart;
  return true;
}

bool intersectAnalytic(const Shape& s, const dvec3& ow, const dvec3& dw, double tMin, double tMax,
                       double* t, int* part) {
  dvec3 o = s.Linv * (ow - s.T);
  dvec3 d = s.Linv * dw;
  *part = 0;
  switch (s.type) {
    case ShapeType::Sphere: return intersectSphereLocal(o, d, s.radius, tMin, tMax, t);
    case ShapeType::Disk: return intersectDiskLocal(o, d, s.radius, tMin, tMax, t);
    case ShapeType::Cylinder:
      return intersectCylinderLocal(o, d, s.radius, s.height, s.caps, tMin, tMax, t, part);
    default: return false;
  }
}

// ---- Surface evaluation ---------------------------------------------------------------------

namespace {
inline float phiOf(double y, double x) {
  double phi = std::atan2(y, x);
  if (phi < 0.0) phi += 2.0 * 3.14159265358979323846;
  return float(phi);
}
}  // namespace

void surfaceAt(const Shape& s, const Ray& ray, float t, uint32_t prim, int part, float u, float v,
               Hit* h) {
  h->prim = prim;
  h->part = part;
  if (s.type == ShapeType::Mesh) {
    uint32_t i0 = s.indices[3 * prim], i1 = s.indices[3 * prim + 1], i2 = s.indices[3 * prim + 2];
    float b0 = 1.0f - u - v;
    const Vec3 &p0 = s.P[i0], &p1 = s.P[i1], &p2 = s.P[i2];
    h->p = b0 * p0 + u * p1 + v * p2;
    h->ng = s.triN[prim];
    if (!s.N.empty()) {
      Vec3 n = b0 * s.N[i0] + u * s.N[i1] + v * s.N[i2];
      float l = glm::length(n);
      h->ns = (l > 0.0f && std::isfinite(l)) ? n * (1.0f / l) : h->ng;
      if (glm::dot(h->ns, h->ng) < 0.0f) h->ns = -h->ns;
    } else {
      h->ns = h->ng;
    }
    h->tex.uv = s.UV.empty() ? Vec2(u, v) : b0 * s.UV[i0] + u * s.UV[i1] + v * s.UV[i2];
    h->tex.st = s.ST.empty() ? Vec2(h->p) : b0 * s.ST[i0] + u * s.ST[i1] + v * s.ST[i2];
  } else {
    dvec3 pw = dvec3(ray.o) + double(t) * dvec3(ray.d);
    dvec3 po = s.Linv * (pw - s.T);
    dvec3 no(0.0, 0.0, 1.0);
    double r = s.radius;
    switch (s.type) {
      case ShapeType::Sphere: {
        double l = glm::length(po);
        no = l > 0.0 ? po * (1.0 / l) : dvec3(0, 0, 1);
        po = no * r;  // reproject onto the surface
        if (s.needsUV)
          h->tex.uv = Vec2(phiOf(po.y, po.x) / (2.0f * kPi),
                           1.0f - float(std::acos(std::clamp(po.z / r, -1.0, 1.0))) / kPi);
        h->tex.st = Vec2(float(po.x), float(po.y));
        break;
      }
      case ShapeType::Disk:
        po.z = 0.0;
        h->tex.uv = Vec2(float(po.x / (2 * r) + 0.5), float(po.y / (2 * r) + 0.5));
        h->tex.st = Vec2(float(po.x), float(po.y));
        break;
      default: {  // cylinder
        if (part == kCylSide) {
          double l = std::sqrt(po.x * po.x + po.y * po.y);
          if (l > 0.0) {
            po.x *= r / l;
            po.y *= r / l;
            no = dvec3(po.x / r, po.y / r, 0.0);
          } else {
            no = dvec3(1, 0, 0);
          }
          if (s.needsUV) {
            float phi = phiOf(po.y, po.x);
            h->tex.uv = Vec2(phi / (2.0f * kPi), float(po.z / s.height + 0.5));
            h->tex.st = Vec2(float(phi * r), float(po.z));
          } else {
            h->tex.st = Vec2(0.0f, float(po.z));  // phi * r needs atan2: only when textured
          }
        } else {
          po.z = part == kCylTop ? 0.5 * s.height : -0.5 * s.height;
          no = dvec3(0, 0, part == kCylTop ? 1.0 : -1.0);
          h->tex.uv = Vec2(float(po.x / (2 * r) + 0.5), float(po.y / (2 * r) + 0.5));
          h->tex.st = Vec2(float(po.x), float(po.y));
        }
        break;
      }
    }
    h->p = Point3(s.L * po + s.T);
    h->ng = Vec3(glm::normalize(s.Nmat * no));
    h->ns = h->ng;
  }
  h->eps = offsetEpsilon(h->p, s.extent);
}

// ---- Area sampling ------------------------------------------------------------------------

ShapeSample sampleShapeArea(const Shape& s, Vec2 u, float u3) {
  ShapeSample ss;
  if (s.parallelogram) {
    ss.p = s.corner + u.x * s.e1 + u.y * s.e2;
    ss.n = s.pnormal;
    ss.pdfArea = float(1.0 / s.area);
    return ss;
  }
  if (s.type == ShapeType::Mesh) {
    size_t n = s.triCdf.size();
    size_t tri = std::lower_bound(s.triCdf.begin(), s.triCdf.end(), double(u3)) - s.triCdf.begin();
    tri = std::min(tri, n - 1);
    Vec2 b = sampleUniformTriangle(u);
    const Vec3 &p0 = s.P[s.indices[3 * tri]], &p1 = s.P[s.indices[3 * tri + 1]],
               &p2 = s.P[s.indices[3 * tri + 2]];
    ss.p = b.x * p0 + b.y * p1 + (1.0f - b.x - b.y) * p2;
    ss.n = s.triN[tri];
    ss.pdfArea = float(1.0 / s.area);
    return ss;
  }
  dvec3 po, no;
  double r = s.radius;
  switch (s.type) {
    case ShapeType::Sphere: {
      Vec3 w = sampleUniformSphere(u);
      no = dvec3(w);
      po = r * no;
      break;
    }
    case ShapeType::Disk: {
      Vec2 d = sampleUniformDiskConcentric(u);
      po = dvec3(r * d.x, r * d.y, 0.0);
      no = dvec3(0, 0, 1);
      break;
    }
    default: {
      const double pi = 3.14159265358979323846;
      double side = 2.0 * pi * r * s.height;
      double pickSide = side / s.objectArea;
      if (double(u3) < pickSide) {
        double phi = 2.0 * pi * u.y;
        po = dvec3(r * std::cos(phi), r * std::sin(phi), (u.x - 0.5) * s.height);
        no = dvec3(std::cos(phi), std::sin(phi), 0.0);
      } else {
        bool top = (double(u3) - pickSide) < 0.5 * (1.0 - pickSide);
        Vec2 d = sampleUniformDiskConcentric(u);
        po = dvec3(r * d.x, r * d.y, (top ? 0.5 : -0.5) * s.height);
        no = dvec3(0, 0, top ? 1.0 : -1.0);
      }
      break;
    }
  }
  dvec3 nw = s.Nmat * no;
  double jac = std::abs(s.detL) * glm::length(nw);  // Nanson: dA_w = |det L| |L^-T n| dA_o
  ss.p = Point3(s.L * po + s.T);
  ss.n = Vec3(glm::normalize(nw));
  ss.pdfArea = float(1.0 / (s.objectArea * jac));
  return ss;
}

float shapePdfArea(const Shape& s, const Hit& h) {
  if (s.type == ShapeType::Mesh) return float(1.0 / s.area);
  dvec3 no = glm::normalize(glm::transpose(s.L) * dvec3(h.ng));
  double jac = std::abs(s.detL) * glm::length(s.Nmat * no);
  return float(1.0 / (s.objectArea * jac));
}

}  // namespace inim
