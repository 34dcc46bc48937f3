#include "field/ray_table.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "core/ray_check.h"
#include "core/format.h"
#include "core/image.h"
#include "core/npy.h"
#include "core/parallel.h"
#include "core/file_kinds.h"
#include "core/rng.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace inim {

namespace {

constexpr int kExrWidth = 4096;  // rows of a wrapped EXR table
const std::vector<std::string> kRayChannels = {"ox", "oy", "oz", "dx", "dy", "dz", "near", "far"};

// Rows of a table file as (rows, cols) floats, with the channel names for EXR.
NpyArray readTable(const std::string& path, std::vector<std::string>& channels) {
  if (requireFileKind(path, "file", {FileKind::Npy, FileKind::Exr}, "a .npy or .exr table", path) == FileKind::Npy)
    return readNpy(path);
  Image img = readImage(path, false);
  channels = img.channels;
  NpyArray a;
  a.rows = int64_t(img.width) * img.height;
  a.cols = img.numChannels();
  a.data = std::move(img.data);
  return a;
}

float srgbToLinear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

RecordingField::RecordingField(size_t numQueries, int spp, const Point3& lo, const Point3& hi) : lo_(lo), hi_(hi) {
  table_.spp = spp;
  table_.rays.resize(numQueries);
  for (auto& r : table_.rays) r.tNear = 0.0f, r.tFar = -1.0f;
}

void RecordingField::query(std::span<const FieldRay> rays, std::span<const SampledWavelengths>,
                           std::span<FieldSample> out, uint64_t) const {
  for (size_t i = 0; i < rays.size(); ++i) {
    const size_t k = size_t(rays[i].id) * size_t(table_.spp) + rays[i].sample;
    if (k < table_.rays.size()) table_.rays[k] = rays[i];
    out[i] = FieldSample{};
  }
}

void writeRayTable(const std::string& path, const RayTable& t) {
  const size_t n = t.rays.size();
  auto fill = [&](float* row, const FieldRay& r) {
    row[0] = r.o.x, row[1] = r.o.y, row[2] = r.o.z;
    row[3] = r.d.x, row[4] = r.d.y, row[5] = r.d.z;
    row[6] = r.tNear, row[7] = r.tFar;
  };
  if (isFileKind(path, FileKind::Npy)) {
    NpyArray a;
    a.rows = int64_t(n), a.cols = 8;
    a.data.resize(n * 8);
    for (size_t i = 0; i < n; ++i) fill(&a.data[i * 8], t.rays[i]);
    writeNpy(path, a);
    return;
  }
  const int w = int(std::min<size_t>(std::max<size_t>(n, 1), kExrWidth));
  const int h = int((n + size_t(w) - 1) / size_t(w));
  Image img(w, std::max(h, 1), kRayChannels);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    float* row = &img.data[i * 8];
    if (i < n) fill(row, t.rays[i]);
    else row[6] = 0.0f, row[7] = -1.0f;
  }
  writeImage(img, path);
}

namespace {

// The door every query ray passes (core/ray_check.h), and an interval from a finite near >= 0;
// the EXR's padding rows (all zero, far = -1: no query) pass as they are.
void checkQueryRay(const FieldRay& r, const std::string& path, int64_t row) {
  const bool padding = r.o == Point3(0.0f) && r.d == Vec3(0.0f) && r.tNear == 0.0f && r.tFar == -1.0f;
  if (padding) return;
  const std::string where = "row " + std::to_string(row);
  checkRay(Vec3d(r.o), Vec3d(r.d), path, where);
  if (!(r.tNear >= 0.0f && std::isfinite(r.tNear)) || std::isnan(r.tFar))  // far < near: no query; far = inf
    throw InputError(path, where, formatText("near %.9g, far %.9g", r.tNear, r.tFar),
                     "a finite near >= 0 and a far that is a number (infinity allowed; below near: no query)");
}

}  // namespace

RayTable readRayTable(const std::string& path, int spp) {
  std::vector<std::string> ch;
  NpyArray a = readTable(path, ch);
  if (a.cols != 8) throw InputError(path, "shape", std::to_string(a.cols) + " columns", "8 (ox oy oz dx dy dz near far)");
  // EXR stores channels sorted by name: look them up.
  int col[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  if (!ch.empty())
    for (int k = 0; k < 8; ++k) {
      auto it = std::find(ch.begin(), ch.end(), kRayChannels[size_t(k)]);
      if (it == ch.end()) throw InputError(path, "channels", "no " + kRayChannels[size_t(k)], "ox oy oz dx dy dz near far");
      col[k] = int(it - ch.begin());
    }
  RayTable t;
  t.spp = spp;
  t.rays.resize(size_t(a.rows));
  for (int64_t i = 0; i < a.rows; ++i) {
    FieldRay& r = t.rays[size_t(i)];
    r.o = Point3(a.at(i, col[0]), a.at(i, col[1]), a.at(i, col[2]));
    r.d = Vec3(a.at(i, col[3]), a.at(i, col[4]), a.at(i, col[5]));
    r.tNear = a.at(i, col[6]), r.tFar = a.at(i, col[7]);
    checkQueryRay(r, path, i);
    r.id = uint64_t(i) / uint64_t(spp);
    r.sample = uint32_t(uint64_t(i) % uint64_t(spp));
  }
  return t;
}

ColorTableField ColorTableField::load(const std::string& path, int spp, size_t numQueries, ColorEncoding enc,
                                      const Point3& lo, const Point3& hi) {
  std::vector<std::string> ch;
  NpyArray a = readTable(path, ch);
  ColorTableField f;
  f.file_ = path;
  f.spp_ = spp;
  f.lo_ = lo, f.hi_ = hi;
  int ir = 0, ig = 1, ib = 2, ia = a.cols > 3 ? 3 : -1, iz = a.cols > 4 ? 4 : -1;
  if (!ch.empty()) {  // EXR: by channel name
    auto find = [&](const char* n) {
      auto it = std::find(ch.begin(), ch.end(), n);
      return it == ch.end() ? -1 : int(it - ch.begin());
    };
    ir = find("R"), ig = find("G"), ib = find("B"), ia = find("A"), iz = find("Z");
    if (ir < 0 || ig < 0 || ib < 0)
      throw InputError(path, "channels", std::to_string(ch.size()) + " channels without R, G, B", "R G B [A [Z]]");
    // Padding pixels of the wrapped layout are dropped.
    if (size_t(a.rows) >= numQueries && size_t(a.rows) - numQueries < size_t(kExrWidth)) a.rows = int64_t(numQueries);
  } else if (a.cols < 3 || a.cols > 5) {
    throw InputError(path, "shape", "(" + std::to_string(a.rows) + ", " + std::to_string(a.cols) + ")",
                     "(N, 3), (N, 4) or (N, 5): R G B [A [depth]] per query ray");
  }
  if (size_t(a.rows) != numQueries)
    throw InputError(path, "shape", std::to_string(a.rows) + " rows",
                     std::to_string(numQueries) + " (one per query ray of this display, layout and spp: write the rays "
                     "with the same options)");
  f.rgba_.resize(numQueries * 4);
  f.hasDepth_ = iz >= 0;
  if (f.hasDepth_) f.depth_.resize(numQueries);
  for (size_t i = 0; i < numQueries; ++i) {
    const int64_t r = int64_t(i);
    float c[4] = {a.at(r, ir), a.at(r, ig), a.at(r, ib), ia >= 0 ? a.at(r, ia) : 1.0f};
    for (float v : c)
      if (!std::isfinite(v))
        throw InputError(path, "row " + std::to_string(i), std::to_string(v), "finite colours and opacity");
    for (int k = 0; k < 3; ++k) f.rgba_[i * 4 + k] = enc == ColorEncoding::SRGB ? srgbToLinear(c[k]) : c[k];
    f.rgba_[i * 4 + 3] = std::clamp(c[3], 0.0f, 1.0f);  // coverage
    if (f.hasDepth_) {
      const float z = a.at(r, iz);
      f.depth_[i] = std::isfinite(z) ? z : kInfinity;
    }
  }
  return f;
}

void ColorTableField::query(std::span<const FieldRay> rays, std::span<const SampledWavelengths>,
                            std::span<FieldSample> out, uint64_t) const {
  const size_t n = rgba_.size() / 4;
  for (size_t i = 0; i < rays.size(); ++i) {
    FieldSample s;
    const size_t k = size_t(rays[i].id) * size_t(spp_) + rays[i].sample;
    if (k < n) {
      // Composited over the display's black: the straight colour weighted by its coverage.
      s.opacity = rgba_[k * 4 + 3];
      s.rgb = s.opacity * Vec3(rgba_[k * 4], rgba_[k * 4 + 1], rgba_[k * 4 + 2]);
      if (hasDepth_) s.depth = depth_[k];
    }
    out[i] = s;
  }
}

std::vector<float> answerRayTable(const Field& field, const RayTable& table, uint64_t seed) {
  const size_t n = table.rays.size();
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  const Mat3 toRgb = ColorSystem::xyzToRec709();
  std::vector<float> rows(n * 5, 0.0f);
  constexpr uint64_t kWavelengthSalt = 0x51EC7A1ull;
  constexpr int64_t kBatch = 4096;
  parallelForRange(int64_t(n), [&](int64_t begin, int64_t end) {
    const size_t b0 = size_t(begin), b1 = size_t(end);
    std::vector<FieldRay> rays(table.rays.begin() + std::ptrdiff_t(b0), table.rays.begin() + std::ptrdiff_t(b1));
    std::vector<SampledWavelengths> lambdas;
    if (spectral)
      for (const FieldRay& r : rays) {
        Rng rng = Rng::forSample(seed ^ kWavelengthSalt, r.id, r.sample);
        lambdas.push_back(SampledWavelengths::sampleVisible(rng.uniform()));
      }
    std::vector<FieldSample> out(rays.size());
    for (auto& r : rays)
      if (!(r.tFar >= r.tNear)) r.tFar = r.tNear;
    field.query(rays, lambdas, out, seed);
    for (size_t i = 0; i < rays.size(); ++i) {
      const Vec3 rgb = spectral ? toRgb * sampledToXYZ(out[i].L, lambdas[i]) : out[i].rgb;
      float* row = &rows[(b0 + i) * 5];
      // Straight colour and coverage, so that A * RGB is the field's radiance again.
      const float a = std::isfinite(out[i].opacity) ? std::min(out[i].opacity, 1.0f) : 0.0f;
      const float k = a > 0.0f ? 1.0f / a : 1.0f;
      row[0] = rgb.x * k, row[1] = rgb.y * k, row[2] = rgb.z * k;
      row[3] = a > 0.0f ? a : (rgb.x != 0.0f || rgb.y != 0.0f || rgb.z != 0.0f ? 1.0f : 0.0f);
      row[4] = std::isfinite(out[i].depth) ? out[i].depth : std::numeric_limits<float>::infinity();
    }
  }, nullptr, kBatch);
  return rows;
}

void writeColorTable(const std::string& path, std::vector<float> rows) {
  const size_t n = rows.size() / 5;
  if (isFileKind(path, FileKind::Npy)) {
    NpyArray a;
    a.rows = int64_t(n), a.cols = 5;
    a.data = std::move(rows);
    writeNpy(path, a);
    return;
  }
  const int w = int(std::min<size_t>(std::max<size_t>(n, 1), size_t(kExrWidth)));
  Image img(w, int((n + size_t(w) - 1) / size_t(w)), {"R", "G", "B", "A", "Z"});
  std::copy(rows.begin(), rows.end(), img.data.begin());
  writeImage(img, path);
}

}  // namespace inim
