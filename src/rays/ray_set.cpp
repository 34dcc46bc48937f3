#include "rays/ray_set.h"

#include <algorithm>

#include "core/error.h"

namespace inim {

void checkRays(const RaySet& r, const std::string& file) {
  for (size_t i = 0; i < r.size(); ++i)
    checkRay(Vec3d(r.ox[i], r.oy[i], r.oz[i]), Vec3d(r.dx[i], r.dy[i], r.dz[i]), file, "ray " + std::to_string(i));
}

void RaySet::resize(size_t n) {
  for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz}) v->resize(n);
}

int64_t rayIndex(const EiLayout& L, const RayAddress& a) {
  if (L.isHex()) {
    // The ray of the box pixel (i, j); -1 when EI (k, l) does not own that pixel.
    const int col = L.eiBoxCol0(a.k, a.l) + a.i, row = L.eiBoxRow0(a.k, a.l) + a.j;
    if (col < 0 || row < 0 || col >= L.eiaW || row >= L.eiaH) return -1;
    const int32_t r = L.pixelMap->pixelRay[size_t(row) * size_t(L.eiaW) + size_t(col)];
    if (r < 0 || r < L.eiRayBegin(a.k, a.l) || r >= L.eiRayBegin(a.k, a.l) + L.eiRayCount(a.k, a.l)) return -1;
    return r;
  }
  int64_t lb = L.eiRows - 1 - a.l, jb = L.eiH - 1 - a.j;
  return ((int64_t(a.k) * L.eiRows + lb) * L.eiW + a.i) * L.eiH + jb;
}

RayAddress rayAddress(const EiLayout& L, int64_t r) {
  RayAddress a;
  if (L.isHex()) {
    const auto& st = L.pixelMap->eiRayStart;
    const int64_t e = int64_t(std::upper_bound(st.begin(), st.end(), r) - st.begin()) - 1;
    L.eiFromOrder(e, a.k, a.l);
    const int32_t px = L.pixelMap->rayPixel[size_t(r)];
    a.i = px % L.eiaW - L.eiBoxCol0(a.k, a.l);
    a.j = px / L.eiaW - L.eiBoxRow0(a.k, a.l);
    return a;
  }
  int64_t jb = r % L.eiH;
  r /= L.eiH;
  a.i = int(r % L.eiW);
  r /= L.eiW;
  int64_t lb = r % L.eiRows;
  a.k = int(r / L.eiRows);
  a.l = int(L.eiRows - 1 - lb);
  a.j = int(L.eiH - 1 - jb);
  return a;
}

PixelCoord eiaPixel(const EiLayout& L, const RayAddress& a) {
  return {L.eiBoxCol0(a.k, a.l) + a.i, L.eiBoxRow0(a.k, a.l) + a.j};
}

PixelCoord panelPixel(const EiLayout& L, const RayAddress& a) {
  PixelCoord p = eiaPixel(L, a);
  return {p.col + L.panelCol0, p.row + L.panelRow0};
}

// The EI whose span [start, start + n) holds `x`, by binary search over sorted starts.
static std::optional<std::pair<int, int>> findEi(const std::vector<int>& starts, int n, int x) {
  auto it = std::upper_bound(starts.begin(), starts.end(), x);
  if (it == starts.begin()) return std::nullopt;
  int k = int(it - starts.begin()) - 1;
  int local = x - starts[size_t(k)];
  if (local >= n) return std::nullopt;
  return std::make_pair(k, local);
}

std::optional<RayAddress> addressAtEiaPixel(const EiLayout& L, PixelCoord p) {
  if (p.col < 0 || p.row < 0 || p.col >= L.eiaW || p.row >= L.eiaH) return std::nullopt;
  if (L.isHex()) {
    int k, l;
    if (!L.eiAtPixel(p.col, p.row, k, l)) return std::nullopt;
    return RayAddress{k, l, p.col - L.eiBoxCol0(k, l), p.row - L.eiBoxRow0(k, l)};
  }
  auto cx = findEi(L.eiCol0, L.eiW, p.col);
  auto cy = findEi(L.eiRow0, L.eiH, p.row);
  if (!cx || !cy) return std::nullopt;
  return RayAddress{cx->first, cy->first, cx->second, cy->second};
}

std::optional<RayAddress> addressAtPanelPixel(const EiLayout& L, PixelCoord p) {
  return addressAtEiaPixel(L, {p.col - L.panelCol0, p.row - L.panelRow0});
}

}  // namespace inim
