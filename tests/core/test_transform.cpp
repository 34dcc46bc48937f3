#include <gtest/gtest.h>

#include "core/error.h"
#include "core/transform.h"

using namespace inim;

TEST(Transform, ComposeAndInvertRoundTrip) {
  Transform t = Transform::translate({1, 2, 3}) * Transform::rotateXYZ({10, 20, 30}) *
                Transform::scale({2, 2, 2});
  Point3d p{0.3, -0.7, 5.0};
  Point3d q = t.inverse().point(t.point(p));
  EXPECT_NEAR(glm::length(q - p), 0.0, 1e-12);
  EXPECT_NEAR(t.scaleFactor(), 2.0, 1e-12);
}

TEST(Transform, RotationAboutZ) {
  Vec3d v = Transform::rotate(90, {0, 0, 1}).vector(Vec3d{1, 0, 0});
  EXPECT_NEAR(v.x, 0.0, 1e-12);
  EXPECT_NEAR(v.y, 1.0, 1e-12);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
  Transform t = Transform::scale({1, 4, 1});
  Vec3d tangent = t.vector(Vec3d{1, -1, 0});
  Vec3d n = t.normal(Vec3d{1, 1, 0});
  EXPECT_NEAR(glm::dot(tangent, n), 0.0, 1e-12);
}

TEST(Transform, SingularPlacementIsAnInputError) {
  EXPECT_THROW(Transform::scale({1, 0, 1}, "placement.scale"), InputError);
  glm::dmat4 m(1.0);
  m[0][0] = std::nan("");
  EXPECT_THROW(Transform::fromMatrix(m), InputError);
  try {
    Transform::scale({0, 0, 0}, "placement.scale");
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "placement.scale");
  }
}
