#include "camera/exit_pupil.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

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

ExitPupilBounds::ExitPupilBounds(const LensSystem& lens, double rMaxMm, const Settings& st)
    : rearZ_(lens.lastVertexZ()), rMax_(std::max(rMaxMm, 1e-9)) {
  const int nBins = std::max(1, st.intervals);
  const int grid = std::max(4, st.grid);
  const int nR = std::max(2, st.radialSamples);
  window_ = 1.5 * lens.surfaces().back().semiAperture();
  const double cell = 2.0 * window_ / grid;
  const double zS = lens.sensorZ();
  std::vector<std::vector<double>> indices;
  for (double l : st.wavelengthsNm) indices.push_back(lens.indicesAt(l));
  if (indices.empty()) indices.push_back(lens.indicesAt(kLensReferenceLambdaNm));
  boxes_.assign(size_t(nBins), PupilBox{});
  tbb::parallel_for(0, nBins, [&](int bin) {
    PupilBox box;
    for (int k = 0; k < nR; ++k) {
      const double r = rMax_ * (bin + double(k) / (nR - 1)) / nBins;
      const Point3d film(r, 0.0, zS);
      for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
          const Vec2d q(-window_ + (i + 0.5) * cell, -window_ + (j + 0.5) * cell);
          bool passes = false;
          for (const auto& idx : indices) {
            LensRay ray{film, glm::normalize(Point3d(q.x, q.y, rearZ_) - film)};
            if (lens.traceWithIndices(ray, idx.data(), TraceDirection::ImageToObject).ok()) {
              passes = true;
              break;
            }
          }
          if (passes) box.extend(q);
        }
    }
    if (!box.empty) {
      const double e = 1.5 * cell;
      box.lo -= Vec2d(e);
      box.hi += Vec2d(e);
    }
    boxes_[size_t(bin)] = box;
  });
}

const PupilBox& ExitPupilBounds::box(double r) const {
  int bin = int(r / rMax_ * double(boxes_.size()));
  bin = std::clamp(bin, 0, int(boxes_.size()) - 1);
  return boxes_[size_t(bin)];
}

bool ExitPupilBounds::sample(const Vec2d& s, const Vec2& u, Point3d& rearPoint, double& pdfArea) const {
  const double r = std::sqrt(s.x * s.x + s.y * s.y);
  const PupilBox& b = box(r);
  if (b.empty) {
    pdfArea = 0.0;
    return false;
  }
  const Vec2d q(b.lo.x + double(u.x) * (b.hi.x - b.lo.x), b.lo.y + double(u.y) * (b.hi.y - b.lo.y));
  // Rotate from the +x axis to the sensor point's polar angle.
  const double c = r > 0.0 ? s.x / r : 1.0, sn = r > 0.0 ? s.y / r : 0.0;
  rearPoint = Point3d(c * q.x - sn * q.y, sn * q.x + c * q.y, rearZ_);
  pdfArea = 1.0 / b.area();
  return true;
}

}  // namespace inim
