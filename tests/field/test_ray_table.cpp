#include <gtest/gtest.h>

#include <cmath>

#include "core/npy.h"
#include "expect_input_error.h"
#include "field/ray_table.h"
#include "scratch_dir.h"

using namespace inim;

namespace {
ScratchDir scratch("ray_table");

std::vector<FieldRay> someRays(int ids, int spp) {
  std::vector<FieldRay> rays;
  for (int id = 0; id < ids; ++id)
    for (int k = 0; k < spp; ++k) {
      FieldRay r;
      r.o = Point3(float(id), float(k), 100.0f);
      r.d = glm::normalize(Vec3(0.1f * float(id), -0.2f, -1.0f));
      r.tNear = 0.0f;
      r.tFar = id == 2 ? -1.0f : kInfinity;  // id 2 never reaches the VCP
      r.id = uint64_t(id);
      r.sample = uint32_t(k);
      rays.push_back(r);
    }
  return rays;
}
}  // namespace

// Rays arrive in any batch order (threads); the table is keyed by id * spp + sample.
TEST(RayTable, RecordingFieldKeysRaysByIdAndSampleWhateverTheBatchOrder) {
  const int ids = 5, spp = 3;
  std::vector<FieldRay> rays = someRays(ids, spp);
  std::reverse(rays.begin(), rays.end());
  RecordingField rec(size_t(ids * spp), spp, Point3(-1.0f), Point3(1.0f));
  std::vector<FieldSample> out(rays.size());
  rec.query(std::span<const FieldRay>(rays).subspan(0, 7), {}, std::span<FieldSample>(out).subspan(0, 7), 1);
  rec.query(std::span<const FieldRay>(rays).subspan(7), {}, std::span<FieldSample>(out).subspan(7), 1);
  for (const FieldSample& s : out) EXPECT_EQ(s.opacity, 0.0f);
  const RayTable& t = rec.table();
  for (int id = 0; id < ids; ++id)
    for (int k = 0; k < spp; ++k) {
      const FieldRay& r = t.rays[size_t(id * spp + k)];
      EXPECT_EQ(r.id, uint64_t(id));
      EXPECT_EQ(r.sample, uint32_t(k));
      EXPECT_EQ(r.o.x, float(id));
    }
}

TEST(RayTable, NpyAndExrTablesRoundTripExactly) {
  RayTable t;
  t.spp = 2;
  t.rays = someRays(4100, 2);  // more than one EXR row of 4096
  for (const char* name : {"rays.npy", "rays.exr"}) {
    const std::string p = scratch.path(name);
    writeRayTable(p, t);
    RayTable u = readRayTable(p, 2);
    ASSERT_GE(u.rays.size(), t.rays.size()) << name;
    for (size_t i = 0; i < t.rays.size(); ++i) {
      EXPECT_EQ(u.rays[i].o, t.rays[i].o);
      EXPECT_EQ(u.rays[i].d, t.rays[i].d);
      EXPECT_EQ(u.rays[i].tFar, t.rays[i].tFar);
      EXPECT_EQ(u.rays[i].id, t.rays[i].id);
      EXPECT_EQ(u.rays[i].sample, t.rays[i].sample);
    }
    for (size_t i = t.rays.size(); i < u.rays.size(); ++i) EXPECT_LT(u.rays[i].tFar, u.rays[i].tNear);  // padding
  }
}

TEST(RayTable, ColorTableAnswersByIndexAndLinearisesSrgb) {
  const int ids = 6, spp = 2;
  NpyArray c;
  c.rows = ids * spp, c.cols = 5;
  for (int i = 0; i < ids * spp; ++i)
    for (float v : {0.5f, float(i) / 16.0f, 1.0f, 0.75f, 10.0f + float(i)}) c.data.push_back(v);
  const std::string p = scratch.path("colors.npy");
  writeNpy(p, c);
  ColorTableField srgb = ColorTableField::load(p, spp, size_t(ids * spp), ColorEncoding::SRGB, Point3(0), Point3(1));
  ColorTableField lin = ColorTableField::load(p, spp, size_t(ids * spp), ColorEncoding::Linear, Point3(0), Point3(1));
  EXPECT_TRUE(lin.hasDepth());
  std::vector<FieldRay> rays = someRays(ids, spp);
  std::vector<FieldSample> a(rays.size()), b(rays.size());
  srgb.query(rays, {}, a, 1);
  lin.query(rays, {}, b, 1);
  // A = 0.75 is coverage: the colour composited over black, in linear light.
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_NEAR(a[i].rgb.x, 0.75f * 0.214041f, 1e-5f);  // sRGB 0.5 -> linear
    EXPECT_FLOAT_EQ(a[i].rgb.z, 0.75f);
    EXPECT_FLOAT_EQ(b[i].rgb.y, 0.75f * float(i) / 16.0f);
    EXPECT_FLOAT_EQ(b[i].opacity, 0.75f);
    EXPECT_FLOAT_EQ(b[i].depth, 10.0f + float(i));
  }
}

// Without an A column every ray is fully covered; without a depth column the field says it
// answers no depth (hits then come from coverage alone). A outside [0, 1] is clamped.
TEST(RayTable, ColorTableWithoutDepthOrOpacityAndClampedCoverage) {
  for (int cols : {3, 4}) {
    NpyArray c;
    c.rows = 3, c.cols = cols;
    for (float a : {-0.5f, 0.5f, 1.5f}) {
      for (float v : {0.2f, 0.4f, 0.6f}) c.data.push_back(v);
      if (cols == 4) c.data.push_back(a);
    }
    const std::string p = scratch.path("nodepth.npy");
    writeNpy(p, c);
    ColorTableField f = ColorTableField::load(p, 1, 3, ColorEncoding::Linear, Point3(0), Point3(1));
    EXPECT_FALSE(f.answersDepth());
    std::vector<FieldRay> rays = someRays(3, 1);
    std::vector<FieldSample> out(3);
    f.query(rays, {}, out, 1);
    const float expectA[3] = {cols == 3 ? 1.0f : 0.0f, cols == 3 ? 1.0f : 0.5f, 1.0f};
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_FLOAT_EQ(out[i].opacity, expectA[i]) << cols << " columns, row " << i;
      EXPECT_FLOAT_EQ(out[i].rgb.y, 0.4f * expectA[i]);
      EXPECT_FALSE(std::isfinite(out[i].depth));
    }
  }
}

TEST(RayTable, ColorTablesOfTheWrongShapeOrWithNanAreInputErrors) {
  NpyArray c;
  c.rows = 4, c.cols = 3;
  c.data.assign(12, 0.5f);
  const std::string p = scratch.path("short.npy");
  writeNpy(p, c);
  InputError e = expectInputError([&] { ColorTableField::load(p, 1, 5, ColorEncoding::SRGB, Point3(0), Point3(1)); });
  EXPECT_EQ(e.file(), p);
  EXPECT_EQ(e.key(), "shape");
  c.cols = 2, c.rows = 6;
  writeNpy(p, c);
  EXPECT_EQ(expectInputError([&] { ColorTableField::load(p, 1, 6, ColorEncoding::SRGB, Point3(0), Point3(1)); }).key(), "shape");
  c.cols = 3, c.rows = 4;
  c.data[7] = std::nanf("");
  writeNpy(p, c);
  EXPECT_EQ(expectInputError([&] { ColorTableField::load(p, 1, 4, ColorEncoding::SRGB, Point3(0), Point3(1)); }).key(), "row 2");
}
