// The model file: exact round trip, and foreign, truncated, corrupt or newer files rejected
// with an InputError that names the path.
#include <gtest/gtest.h>

#include <cstring>

#include "core/rng.h"
#include "fixtures.h"
#include "radiance/grid_io.h"
#include "radiance/volume_renderer.h"

using namespace inim;
using namespace fixtures;

namespace {

VoxelGrid sampleGrid() {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f, -0.5f, -0.75f), Point3(1.0f, 0.5f, 0.75f),
                                  glm::ivec3(9, 6, 7), 2, DensityActivation::Softplus,
                                  Vec3(0.0f), 0.05f);
  Rng rng(11, 0);
  for (float& d : g.density) d = -3.0f + 6.0f * rng.uniform();
  for (float& c : g.color) c = -2.0f + 4.0f * rng.uniform();
  return g;
}

}  // namespace

TEST(GridIo, RoundTripGivesIdenticalRenders) {
  ScratchDir dir("radiance_io");
  VoxelGrid g = sampleGrid();
  g.metadata = R"({"dataset": "x/transforms.json", "units": "mm"})";
  std::string path = dir.path("model.inimrf");
  saveVoxelGrid(g, path);
  VoxelGrid h = loadVoxelGrid(path);
  EXPECT_EQ(h.metadata, g.metadata);
  EXPECT_EQ(h.lo, g.lo);
  EXPECT_EQ(h.hi, g.hi);
  EXPECT_EQ(h.res, g.res);
  EXPECT_EQ(h.shDegree, g.shDegree);
  EXPECT_EQ(h.activation, g.activation);
  EXPECT_EQ(h.background, g.background);
  EXPECT_EQ(h.densityScale, g.densityScale);
  EXPECT_TRUE(h.density == g.density);
  EXPECT_TRUE(h.color == g.color);
  VolumeRenderer ra(g), rb(h);
  std::vector<RenderRay> rays;
  Rng rng(5, 0);
  for (int i = 0; i < 200; ++i)
    rays.push_back(RenderRay{Point3(0, 0, 3),
                             Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, -2.0f)});
  std::vector<RadianceSample> a(rays.size()), b(rays.size());
  ra.render(rays, a);
  rb.render(rays, b);
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(a[i].rgb, b[i].rgb);
    EXPECT_EQ(a[i].opacity, b[i].opacity);
    EXPECT_EQ(a[i].depth, b[i].depth);
    hits += a[i].opacity > 0.1f;
  }
  EXPECT_GT(hits, 50);
}

TEST(GridIo, RejectsForeignTruncatedCorruptAndNewerFiles) {
  ScratchDir dir("radiance_io_bad");
  std::string good = dir.path("good.inimrf");
  saveVoxelGrid(sampleGrid(), good);
  std::string bytes = readBytes(good);
  auto expectHeaderError = [&](const std::string& content, const std::string& name) {
    std::string p = dir.path(name);
    writeBytes(p, content);
    InputError e = expectInputError([&] { loadVoxelGrid(p); });
    EXPECT_EQ(e.file(), p);
    EXPECT_EQ(e.key(), "header");
    EXPECT_NE(e.expected().find("inim radiance-field model"), std::string::npos);
    return e;
  };
  expectHeaderError("P6\n2 2\n255\nxxxxxxxxxxxxxxxxxxxxxxxxxxxx", "foreign.ppm");
  expectHeaderError("", "empty.inimrf");
  expectHeaderError(bytes.substr(0, 12), "short-header.inimrf");
  expectHeaderError(bytes.substr(0, 40), "truncated-header.inimrf");
  expectHeaderError(bytes.substr(0, bytes.size() - 4), "truncated-data.inimrf");
  std::string corrupt = bytes;
  corrupt[corrupt.size() - 100] ^= 0x5a;
  expectHeaderError(corrupt, "corrupt-data.inimrf");
  std::string badRes = bytes;
  int32_t res = -5;
  std::memcpy(&badRes[16 + 24], &res, 4);  // res.x, after lo[3] and hi[3]
  expectHeaderError(badRes, "bad-res.inimrf");
  std::string newer = bytes;
  uint32_t version = kVoxelGridVersion + 1;
  std::memcpy(&newer[8], &version, 4);
  InputError e = expectHeaderError(newer, "newer.inimrf");
  EXPECT_NE(e.value().find("version"), std::string::npos);
  InputError missing = expectInputError([&] { loadVoxelGrid(dir.path("missing.inimrf")); });
  EXPECT_EQ(missing.key(), "path");
}
