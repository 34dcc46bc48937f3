// Placement resolution: values given one by one replace the base's (a run file's or a model's),
// and a singular result is an InputError naming the setting that made it.
#include <gtest/gtest.h>

#include <cmath>

#include "expect_input_error.h"
#include "field/placement.h"

using namespace inim;

TEST(Placement, GivenValuesReplaceOnlyTheirOwn) {
  Placement base;
  base.scale = Vec3d(2.0);
  base.rotateDeg = {0.0, 90.0, 0.0};
  base.translateMm = {1.0, 2.0, 3.0};
  base.source = "run.json";
  PlacementOverride given;
  given.translateMm = Vec3d(0.0, 0.0, 5.0);
  const Placement p = resolvePlacement(base, given);
  EXPECT_EQ(p.scale, Vec3d(2.0));
  EXPECT_EQ(p.rotateDeg, Vec3d(0.0, 90.0, 0.0));
  EXPECT_EQ(p.translateMm, Vec3d(0.0, 0.0, 5.0));
  EXPECT_EQ(p.source, "command line");
  // A point 1 unit along x: scaled to 2 mm, turned 90 deg about y to -z, then moved.
  const Point3d q = p.toDisplay().point(Point3d(1.0, 0.0, 0.0));
  EXPECT_NEAR(q.x, 0.0, 1e-9);
  EXPECT_NEAR(q.z, 5.0 - 2.0, 1e-9);

  // Nothing given: the base as it is; no base: the identity.
  EXPECT_EQ(resolvePlacement(base, {}).source, "run.json");
  EXPECT_TRUE(resolvePlacement(std::nullopt, {}).isIdentity());
}

TEST(Placement, SingularPlacementNamesTheSetting) {
  PlacementOverride given;
  given.scale = Vec3d(1.0, 0.0, 1.0);
  const InputError e = expectInputError([&] { (void)resolvePlacement(std::nullopt, given); });
  EXPECT_EQ(e.key(), "scale");
  EXPECT_EQ(e.file(), "");
  PlacementOverride rotation;
  rotation.rotateDeg = Vec3d(0.0, std::nan(""), 0.0);
  EXPECT_EQ(expectInputError([&] { (void)resolvePlacement(std::nullopt, rotation); }).key(), "rotate_deg");
  // A base from a file keeps naming the file's key when its own scale is kept.
  Placement fromFile;
  fromFile.source = "run.json";
  fromFile.scaleKey = "placement.scale";
  fromFile.scale = Vec3d(0.0);
  const InputError f = expectInputError([&] { (void)resolvePlacement(fromFile, {}); });
  EXPECT_EQ(f.file(), "run.json");
  EXPECT_EQ(f.key(), "placement.scale");
}
