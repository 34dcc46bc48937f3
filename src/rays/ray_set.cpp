#include "rays/ray_set.h"

#include <algorithm>

namespace inim {

void RaySet::resize(size_t n) {
  for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz}) v->resize(n);
}

int64_t rayIndex(const EiLayout& L, const RayAddress& a) {
  int64_t lb = L.eiRows - 1 - a.l, jb = L.eiH - 1 - a.j;
  return ((int64_t(a.k) * L.eiRows + lb) * L.eiW + a.i) * L.eiH + jb;
}

RayAddress rayAddress(const EiLayout& L, int64_t r) {
  RayAddress a;
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
  return {L.eiCol0[size_t(a.k)] + a.i, L.eiRow0[size_t(a.l)] + a.j};
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
  auto cx = findEi(L.eiCol0, L.eiW, p.col);
  auto cy = findEi(L.eiRow0, L.eiH, p.row);
  if (!cx || !cy) return std::nullopt;
  return RayAddress{cx->first, cy->first, cx->second, cy->second};
}

std::optional<RayAddress> addressAtPanelPixel(const EiLayout& L, PixelCoord p) {
  return addressAtEiaPixel(L, {p.col - L.panelCol0, p.row - L.panelRow0});
}

}  // namespace inim
