// The EIA from a colour table (`inim eia --field-colors`): A is coverage, composited over the
// display's black (rows with A = 0 give no light, A = 0.25 a quarter); a table without depth
// still fills the EIA with no false "empty" warning, no scene bounds and a real exposure; and
// the exchange through answerRayTable reproduces a partly transparent field exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "core/npy.h"
#include "field/ray_table.h"
#include "scratch_dir.h"
#include "synth_test_util.h"

using namespace inim;
using namespace synth_test;

namespace {

ScratchDir scratch("color_table_synthesis");

// One row per query: linear colour (0.3, 0.5, 0.2) of display ray id, A from `coverage(id)`.
template <class Coverage>
std::string writeTable(const std::string& name, size_t rows, int spp, int cols, Coverage coverage) {
  NpyArray a;
  a.rows = int64_t(rows), a.cols = cols;
  for (size_t i = 0; i < rows; ++i) {
    const float v[5] = {0.3f, 0.5f, 0.2f, coverage(i / size_t(spp)), 20.0f};
    a.data.insert(a.data.end(), v, v + cols);
  }
  const std::string p = scratch.path(name);
  writeNpy(p, a);
  return p;
}

// Light of partial coverage plus a background seen through nothing: radiance = A * colour
// (as a volume renders it) on display rays with id % 3 == 0, 1; only background otherwise.
class VeilField final : public Field {
 public:
  FieldEncoding encoding() const override { return FieldEncoding::RGB; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths>, std::span<FieldSample> out,
             uint64_t) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      FieldSample s;
      if (rays[i].id % 3 != 2) {
        s.opacity = rays[i].id % 3 == 0 ? 0.4f : 1.0f;
        s.rgb = s.opacity * Vec3(0.9f, 0.2f, 0.1f) + (1.0f - s.opacity) * Vec3(0.05f);
        s.depth = 12.0f;
      } else {
        s.rgb = Vec3(0.05f);  // background only: no coverage, no depth
      }
      out[i] = s;
    }
  }
  void bounds(Point3& lo, Point3& hi) const override { lo = Point3(-5.0f), hi = Point3(5.0f); }
};

}  // namespace

TEST(ColorTableSynthesis, CoverageCompositesOverTheDisplaysBlack) {
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 5});
  EiLayout L = computeLayout(disp);
  const size_t n = size_t(L.numRays());
  auto cov = [](size_t id) { return id % 3 == 0 ? 0.0f : id % 3 == 1 ? 1.0f : 0.25f; };
  const std::string p = writeTable("coverage.npy", n, 1, 5, cov);
  ColorTableField f = ColorTableField::load(p, 1, n, ColorEncoding::Linear, Point3(kInfinity), Point3(-kInfinity));
  SynthesisSettings s = quietSettings();
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  const Vec3 full(r.drive[3], r.drive[4], r.drive[5]);  // ray 1: A = 1
  ASSERT_GT(full.y, 0.0f);
  for (size_t id = 0; id < n; ++id)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.drive[id * 3 + size_t(c)], cov(id) * full[c], 1e-6f) << "ray " << id;
  // A = 0 rows are misses; A > 0 rows with a finite depth are hits.
  EXPECT_EQ(r.stats.hitRays, n - (n + 2) / 3);
}

TEST(ColorTableSynthesis, TableWithoutDepthFillsTheEiaWithoutSideEffects) {
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 5});
  EiLayout L = computeLayout(disp);
  const size_t n = size_t(L.numRays()) * 2;
  const std::string p = writeTable("rgb.npy", n, 2, 3, [](size_t) { return 1.0f; });
  ColorTableField f = ColorTableField::load(p, 2, n, ColorEncoding::Linear, Point3(kInfinity), Point3(-kInfinity));
  EXPECT_FALSE(f.answersDepth());
  SynthesisSettings s = quietSettings();
  s.spp = 2;
  s.aovs = true;
  s.autoExposure = true;
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  EXPECT_TRUE(r.stats.warnings.empty()) << r.stats.warnings[0];
  EXPECT_TRUE(r.stats.notes.empty()) << r.stats.notes[0];
  EXPECT_FALSE(r.stats.emptyEia);
  EXPECT_FALSE(r.stats.sceneBoundsKnown);
  EXPECT_FALSE(r.stats.sceneClipped);
  EXPECT_FALSE(r.stats.hitDepthsKnown);
  EXPECT_EQ(r.stats.hitRays, uint64_t(L.numRays()));  // A absent: every ray covered
  EXPECT_EQ(r.stats.realRays + r.stats.virtualRays, 0u);
  // The same colour as an opaque field that covers everything: the same exposure and drive.
  MockField wall({{{0.0, 0.0, -1010.0}, 1000.0, Vec3(0.3f, 0.5f, 0.2f), 0.0, nullptr}}, FieldEncoding::RGB);
  SynthesisResult w = synthesizeEia(L, disp.panel, wall, s);
  EXPECT_NE(r.stats.exposureUsed, 1.0);
  EXPECT_NEAR(r.stats.exposureUsed, w.stats.exposureUsed, 1e-6 * w.stats.exposureUsed);
  for (size_t i = 0; i < r.drive.size(); ++i) EXPECT_NEAR(r.drive[i], w.drive[i], 1e-5f);
  // A is the coverage, Z stays empty (no depth), on every EI pixel.
  const int a = r.eia.channelIndex("A"), z = r.eia.channelIndex("Z");
  int px = 0;
  for (int y = 0; y < r.eia.height; ++y)
    for (int x = 0; x < r.eia.width; ++x)
      if (r.eia.at(x, y, a) > 0.0f) {
        ++px;
        EXPECT_EQ(r.eia.at(x, y, z), 0.0f);
      }
  EXPECT_EQ(px, L.numRays());
  EXPECT_NE(summaryText(r.stats, s.gamut).find("real / virtual unknown"), std::string::npos);
}

TEST(ColorTableSynthesis, ExchangeReproducesAPartlyTransparentFieldAndItsBackground) {
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 5});
  EiLayout L = computeLayout(disp);
  SynthesisSettings s = quietSettings();
  s.spp = 2;
  s.aovs = true;
  VeilField veil;
  SynthesisResult direct = synthesizeEia(L, disp.panel, veil, s);
  const size_t n = size_t(L.numRays()) * 2;
  RecordingField rec(n, 2, Point3(-5.0f), Point3(5.0f));
  (void)synthesizeEia(L, disp.panel, rec, s);
  const std::string p = scratch.path("veil.npy");
  writeColorTable(p, answerRayTable(veil, rec.table(), s.seed));
  NpyArray rows = readNpy(p);
  for (int64_t i = 0; i < rows.rows; ++i) {  // straight colour, coverage
    const uint64_t id = uint64_t(i) / 2;
    if (rec.table().rays[size_t(i)].tFar < 0.0f) continue;
    EXPECT_NEAR(rows.at(i, 0), id % 3 == 2 ? 0.05f : id % 3 == 0 ? 0.9f + 0.6f / 0.4f * 0.05f : 0.9f, 1e-5f);
    EXPECT_EQ(rows.at(i, 3), id % 3 == 0 ? 0.4f : 1.0f);
  }
  ColorTableField f = ColorTableField::load(p, 2, n, ColorEncoding::Linear, Point3(kInfinity), Point3(-kInfinity));
  SynthesisResult exchanged = synthesizeEia(L, disp.panel, f, s);
  ASSERT_EQ(direct.eia.data.size(), exchanged.eia.data.size());
  for (size_t i = 0; i < direct.eia.data.size(); ++i) EXPECT_NEAR(direct.eia.data[i], exchanged.eia.data[i], 1e-6f);
  EXPECT_EQ(direct.stats.hitRays, exchanged.stats.hitRays);
}
