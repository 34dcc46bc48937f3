#pragma once
// Ray exchange with external radiance fields (a Nerfstudio model, say): inim writes the
// query rays of a run, another program fills in one colour per ray, and inim reads the
// colours back as a Field, so the rest of the pipeline (EIA, triads, views) runs unchanged.
//
//   RecordingField rec(numRays * spp, spp, lo, hi);     // 1. run synthesis with it
//   synthesizeEia(L, panel, rec, s);  writeRayTable("rays.npy", rec.table());
//   ... python: colours[i] = nerf(origin[i], direction[i], near[i], far[i]) ...
//   ColorTableField f = ColorTableField::load("colors.npy", spp, numRays * spp, ...);
//   synthesizeEia(L, panel, f, s);                       // 2. the same run with the colours
//
// A query ray is keyed by its index id * spp + sample (ids are display-ray indices, samples
// 0..spp-1), so the table's row order is fixed by the display and the run, not by threads.
//
// Files, row i = query ray i:
//  - rays: NPY float32 (N, 8) ox oy oz dx dy dz near far, or an EXR of width min(N, 4096)
//    with channels ox oy oz dx dy dz near far, ray i at pixel (i % W, i / W), padding pixels
//    with near = 0, far = -1. Coordinates are the FIELD frame (after the inverse placement);
//    directions are unit vectors; near = 0 is the VCP; far = inf means unbounded (clip it to
//    the model's far plane); far < near marks a ray that never reaches the VCP (its colour is
//    ignored).
//  - colours: NPY float32/float64 (N, 3 | 4 | 5) R G B [A [depth]], or an EXR laid out like
//    the rays with channels R G B [A [Z]]. A is the ray's coverage in [0, 1] (clamped; 1 if
//    absent) and R G B the colour of what covers it (straight, not multiplied by A): the
//    display shows that colour composited over its own black, A * RGB (in linear light), so
//    a renderer's background never reaches the EIA. depth is the expected distance along the
//    ray in field units, non-finite for a miss. Without depth a ray hits when A >= 0.5
//    (kHalfCoverage) and the EIA's Z channel and real/virtual counts stay empty.
#include <string>
#include <vector>

#include "field/field.h"

namespace inim {

struct RayTable {
  int spp = 1;
  std::vector<FieldRay> rays;  // index id * spp + sample
};

// Answers nothing (opacity 0, no radiance) and records every query ray at its index.
// Queries from several threads are safe: each index is written once.
class RecordingField : public Field {
 public:
  RecordingField(size_t numQueries, int spp, const Point3& lo, const Point3& hi);
  FieldEncoding encoding() const override { return FieldEncoding::RGB; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t seed) const override;
  void bounds(Point3& lo, Point3& hi) const override { lo = lo_, hi = hi_; }
  const RayTable& table() const { return table_; }

 private:
  mutable RayTable table_;
  Point3 lo_, hi_;
};

// NPY or EXR by extension (.npy, .exr). Throws std::runtime_error when writing fails.
void writeRayTable(const std::string& path, const RayTable& t);
// Reads a table written by writeRayTable (for tests and external tools' round trips).
RayTable readRayTable(const std::string& path, int spp);

enum class ColorEncoding { SRGB, Linear };  // NeRFs trained on photos answer sRGB-encoded values

// Coverage from which a table without depth counts a ray as a hit (the half-coverage rule the
// Nerfstudio recipe uses to mark misses: below it a NeRF's median depth is undefined).
constexpr float kHalfCoverage = 0.5f;

// Colours per query ray, answered by index. InputError naming the file when the row count is
// not `numQueries` (the run that wrote the rays must match: display, layout, spp), the column
// count is not 3-5, or a value is not finite.
class ColorTableField : public Field {
 public:
  static ColorTableField load(const std::string& path, int spp, size_t numQueries, ColorEncoding enc,
                              const Point3& lo, const Point3& hi);
  FieldEncoding encoding() const override { return FieldEncoding::RGB; }
  std::string colorSpace() const override { return "lin_rec709"; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t seed) const override;
  void bounds(Point3& lo, Point3& hi) const override { lo = lo_, hi = hi_; }
  bool hasDepth() const { return hasDepth_; }
  bool answersDepth() const override { return hasDepth_; }

 private:
  std::string file_;
  int spp_ = 1;
  std::vector<float> rgba_;   // 4 per row (linear)
  std::vector<float> depth_;  // per row, when given
  bool hasDepth_ = false;
  Point3 lo_, hi_;
};

// One of inim's own fields answering a ray table as an external renderer would (`inim query`):
// N x 5 floats, row i = linear Rec.709 R G B (straight: the field's radiance divided by its
// opacity), opacity and depth (inf when nothing was hit) of ray i, so that A * RGB gives the
// field's radiance back. Light without coverage (a field's background seen through nothing)
// is written with A = 1 and depth inf: a miss that still shows that light. A spectral field is sampled at one visible wavelength packet per ray, drawn from
// (seed, ray id, sample); rays that never reach the VCP (far < near) answer nothing.
std::vector<float> answerRayTable(const Field& field, const RayTable& table, uint64_t seed);
// Writes such rows as ColorTableField::load reads them: .npy (float32 N x 5) or .exr (R G B A
// Z, laid out like the rays). Throws std::runtime_error when writing fails.
void writeColorTable(const std::string& path, std::vector<float> rows);

}  // namespace inim
