#include "camera/exit_pupil.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <string>

#include "core/sampling.h"

namespace inim {

void PupilBox::extend(const Vec2d& p) {
  if (empty) {
    lo = hi = p;
    empty = false;
  } else {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
}

namespace {

// Whether every cell of half-widths h around the points lies in the ellipse inscribed in the box.
bool insideInscribedEllipse(const PupilBox& box, const std::vector<Vec2d>& points, const Vec2d& h) {
  const Vec2d c = 0.5 * (box.lo + box.hi), half = 0.5 * (box.hi - box.lo);
  for (const Vec2d& p : points)
    for (int k = 0; k < 4; ++k) {
      const Vec2d q = (p + Vec2d(k & 1 ? h.x : -h.x, k & 2 ? h.y : -h.y) - c) / half;
      if (glm::dot(q, q) > 1.0) return false;
    }
  return true;
}

}  // namespace

// The passing points of a grid x grid scan of [lo, hi] from nR sensor radii of the bin, and
// their bounding box.
PupilBox ExitPupilBounds::scanBin(const LensSystem& lens, const std::vector<std::vector<double>>& indices, int bin,
                                  int nBins, int nR, int grid, const Vec2d& lo, const Vec2d& hi,
                                  std::vector<Vec2d>& passing) const {
  PupilBox box;
  const Vec2d cell = (hi - lo) / double(grid);
  for (int k = 0; k < nR; ++k) {
    const double r = rMax_ * (bin + double(k) / (nR - 1)) / nBins;
    const Point3d film(r, 0.0, lens.sensorZ());
    for (int j = 0; j < grid; ++j)
      for (int i = 0; i < grid; ++i) {
        const Vec2d q(lo.x + (i + 0.5) * cell.x, lo.y + (j + 0.5) * cell.y);
        for (const auto& idx : indices) {
          LensRay ray{film, glm::normalize(Point3d(q.x, q.y, rearZ_) - film)};
          if (lens.traceWithIndices(ray, idx.data(), TraceDirection::ImageToObject).ok()) {
            box.extend(q);
            passing.push_back(q);
            break;
          }
        }
      }
  }
  return box;
}

ExitPupilBounds::ExitPupilBounds(const LensSystem& lens, double rMaxMm, const Settings& st)
    : rearZ_(lens.lastVertexZ()), rMax_(std::max(rMaxMm, 1e-9)) {
  const int nBins = std::max(1, st.intervals);
  const int grid = std::max(4, st.grid);
  const int nR = std::max(2, st.radialSamples);
  window_ = 1.5 * lens.surfaces().back().semiAperture();
  std::vector<std::vector<double>> indices;
  for (double l : st.wavelengthsNm) indices.push_back(lens.indicesAt(l));
  if (indices.empty()) indices.push_back(lens.indicesAt(kLensReferenceLambdaNm));
  boxes_.assign(size_t(nBins), PupilBox{});
  sampling_.assign(size_t(nBins), PupilBox{});
  tbb::parallel_for(0, nBins, [&](int bin) {
    std::vector<Vec2d> passing;
    const Vec2d coarse(2.0 * window_ / grid);
    PupilBox box = scanBin(lens, indices, bin, nBins, nR, grid, Vec2d(-window_), Vec2d(window_), passing);
    if (box.empty) return;
    box.lo -= 1.5 * coarse;
    box.hi += 1.5 * coarse;
    boxes_[size_t(bin)] = box;
    // The box it found, scanned again at the same grid: the sampled shape as fine as the pupil
    // is small in the window.
    const Vec2d lo = box.lo + 0.5 * coarse, hi = box.hi - 0.5 * coarse;
    passing.clear();
    PupilBox tight = scanBin(lens, indices, bin, nBins, nR, grid, lo, hi, passing);
    if (tight.empty) {
      sampling_[size_t(bin)] = box;
      return;
    }
    const Vec2d cell = (hi - lo) / double(grid);
    tight.lo -= 1.5 * cell;
    tight.hi += 1.5 * cell;
    tight.ellipse = insideInscribedEllipse(tight, passing, 0.5 * cell);
    sampling_[size_t(bin)] = tight;
  });
}

size_t ExitPupilBounds::binOf(double r) const {
  return size_t(std::clamp(int(r / rMax_ * double(boxes_.size())), 0, int(boxes_.size()) - 1));
}

const PupilBox& ExitPupilBounds::box(double r) const {
  return boxes_[binOf(r)];
}

bool ExitPupilBounds::sample(const Vec2d& s, const Vec2& u, Point3d& rearPoint, double& pdfArea) const {
  const double r = std::sqrt(s.x * s.x + s.y * s.y);
  const PupilBox& b = sampling_[binOf(r)];
  if (b.empty) {
    pdfArea = 0.0;
    return false;
  }
  Vec2d q(b.lo.x + double(u.x) * (b.hi.x - b.lo.x), b.lo.y + double(u.y) * (b.hi.y - b.lo.y));
  if (b.ellipse) q = 0.5 * (b.lo + b.hi) + 0.5 * (b.hi - b.lo) * Vec2d(sampleUniformDiskConcentric(u));
  // Rotate from the +x axis to the sensor point's polar angle.
  const double c = r > 0.0 ? s.x / r : 1.0, sn = r > 0.0 ? s.y / r : 0.0;
  rearPoint = Point3d(c * q.x - sn * q.y, sn * q.x + c * q.y, rearZ_);
  pdfArea = 1.0 / b.area();
  return true;
}

namespace {

// Everything a scan reads, as bytes: each surface's shape and its media's indices at the
// scanned wavelengths, the sensor's position, rMax and the settings.
std::string scanKey(const LensSystem& lens, double rMaxMm, const ExitPupilBounds::Settings& st) {
  std::vector<double> v = {rMaxMm, lens.sensorZ(), double(st.intervals), double(st.grid), double(st.radialSamples)};
  std::vector<double> wavelengths = st.wavelengthsNm;
  if (wavelengths.empty()) wavelengths.push_back(kLensReferenceLambdaNm);
  for (double l : wavelengths) {
    v.push_back(l);
    for (double n : lens.indicesAt(l)) v.push_back(n);
  }
  for (const LensSurface& s : lens.surfaces())
    v.insert(v.end(), {s.radiusMm, s.conic, s.thicknessMm, s.apertureMm, s.isStop ? 1.0 : 0.0});
  std::string key(v.size() * sizeof(double), '\0');
  std::memcpy(key.data(), v.data(), key.size());
  return key;
}

}  // namespace

std::shared_ptr<const ExitPupilBounds> ExitPupilBounds::shared(const LensSystem& lens, double rMaxMm,
                                                               const Settings& settings) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const ExitPupilBounds>> scanned;
  const std::string key = scanKey(lens, rMaxMm, settings);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto it = scanned.find(key); it != scanned.end()) return it->second;
  }
  auto bounds = std::make_shared<const ExitPupilBounds>(lens, rMaxMm, settings);
  const std::lock_guard<std::mutex> lock(mutex);
  if (scanned.size() >= 16) scanned.clear();  // a sweep over many lenses keeps only the recent
  return scanned.emplace(key, std::move(bounds)).first->second;
}

}  // namespace inim
