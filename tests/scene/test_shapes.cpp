// Exact analytic intersections and the hard geometric cases: grazing rays, rays along box
// edges, degenerate triangles, micrometre and metre scenes.
#include <gtest/gtest.h>

#include "scene/obj_loader.h"
#include "scene/shapes.h"
#include "scene_test_util.h"

using namespace inim;
using namespace inim::test;

namespace {
const char* kLitSphere = R"({
  "materials": {"white": {"type": "diffuse", "reflectance": 0.8}},
  "objects": [{"type": "sphere", "radius_mm": 10, "material": "white"}],
  "lights": [{"type": "point", "position_mm": [0, 0, 200], "spectrum": 1000}]
})";
}

TEST(Shapes, SphereDistancesExact) {
  auto s = sceneFromString(kLitSphere);
  // Axis ray: t = 100 - 10. Off-axis ray at height b: t = 100 - sqrt(r^2 - b^2).
  for (double b : {0.0, 3.0, 6.0, 9.0, 9.99}) {
    Hit h;
    ASSERT_TRUE(s->intersect(Ray{Point3(float(b), 0, 100), Vec3(0, 0, -1)}, h)) << b;
    double expected = 100.0 - std::sqrt(100.0 - b * b);
    EXPECT_NEAR(h.t, expected, 1e-5 * expected) << "b = " << b;
    EXPECT_NEAR(glm::length(h.p), 10.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(h.ng, glm::normalize(h.p)), 1.0f, 1e-6f);
  }
}

TEST(Shapes, TransformedQuadricsExact) {
  auto s = sceneFromString(R"({
    "materials": {"m": {"type": "diffuse"}},
    "objects": [
      {"type": "sphere", "radius_mm": 2, "scale": [1, 1, 3], "translate_mm": [0, 0, -50], "material": "m"},
      {"type": "disk", "radius_mm": 5, "rotate_deg": [0, 45, 0], "translate_mm": [100, 0, 0], "material": "m"},
      {"type": "cylinder", "radius_mm": 4, "height_mm": 2, "translate_mm": [-100, 0, 0], "material": "m"},
      {"type": "cylinder", "radius_mm": 4, "height_mm": 20, "rotate_deg": [90, 0, 0], "translate_mm": [0, 100, 0], "material": "m"}
    ]})");
  Hit h;
  // Ellipsoid with semi-axis 6 along z, centred at z = -50: hit at z = -44 from z = 0.
  ASSERT_TRUE(s->intersect(Ray{Point3(0, 0, 0), Vec3(0, 0, -1)}, h));
  EXPECT_NEAR(h.t, 44.0f, 44e-6f);
  EXPECT_NEAR(h.ng.z, 1.0f, 1e-6f);
  // Ellipsoid off-axis at x = 1: z = 6 sqrt(1 - 1/4).
  ASSERT_TRUE(s->intersect(Ray{Point3(1, 0, 0), Vec3(0, 0, -1)}, h));
  EXPECT_NEAR(h.t, 50.0 - 6.0 * std::sqrt(0.75), 1e-4);
  // Disk tilted 45 deg about y at x = 100: a ray along -z from (101, 0, 10) meets the plane
  // z = -(x - 100) * tan(45) ... the disk normal is (sin45, 0, cos45): plane x' + z = 0.
  ASSERT_TRUE(s->intersect(Ray{Point3(101, 0, 10), Vec3(0, 0, -1)}, h));
  EXPECT_NEAR(h.t, 11.0f, 11e-6f);
  // Coin (cylinder with caps, axis z, 2 mm thick): from above, the top cap at z = 1.
  ASSERT_TRUE(s->intersect(Ray{Point3(-101, 1, 10), Vec3(0, 0, -1)}, h));
  EXPECT_NEAR(h.t, 9.0f, 9e-6f);
  EXPECT_NEAR(h.ng.z, 1.0f, 1e-6f);
  // From the side: x = -100 + 4 at the rim.
  ASSERT_TRUE(s->intersect(Ray{Point3(-50, 0, 0.5f), Vec3(-1, 0, 0)}, h));
  EXPECT_NEAR(h.t, 46.0f, 46e-6f);
  EXPECT_NEAR(h.ng.x, 1.0f, 1e-6f);
  // A long cylinder rotated 90 deg about x: axis along y. Ray along -z at x = 2 hits the
  // side at z = sqrt(16 - 4).
  ASSERT_TRUE(s->intersect(Ray{Point3(2, 100, 50), Vec3(0, 0, -1)}, h));
  EXPECT_NEAR(h.t, 50.0 - std::sqrt(12.0), 1e-4);
  // Along the axis it meets the cap: y = 100 + 10.
  ASSERT_TRUE(s->intersect(Ray{Point3(0, 200, 0), Vec3(0, -1, 0)}, h));
  EXPECT_NEAR(h.t, 90.0f, 90e-6f);
}

TEST(Shapes, StableQuadraticLocal) {
  // Far-away origin: naive b^2 - 4ac loses everything; the stable form keeps full precision.
  double t;
  ASSERT_TRUE(intersectSphereLocal({0, 0, 1e7}, {0, 0, -1}, 1.0, 0.0, 1e30, &t));
  EXPECT_DOUBLE_EQ(t, 1e7 - 1.0);
  ASSERT_TRUE(intersectSphereLocal({0.5, 0, 1e7}, {0, 0, -1}, 1.0, 0.0, 1e30, &t));
  EXPECT_NEAR(t, 1e7 - std::sqrt(0.75), 1e-8 * 1e7);
  // From inside: the far root.
  ASSERT_TRUE(intersectSphereLocal({0, 0, 0}, {1, 0, 0}, 2.0, 0.0, 1e30, &t));
  EXPECT_DOUBLE_EQ(t, 2.0);
}

TEST(Shapes, GrazingSphereNoNaN) {
  auto s = sceneFromString(kLitSphere);
  SampledWavelengths l = wavelengthsAt(550);
  // Offsets straddling the silhouette b = r: discriminant ~ 0 from both sides.
  for (double rel : {-1e-3, -1e-5, -1e-7, 0.0, 1e-7, 1e-5, 1e-3}) {
    float b = float(10.0 * (1.0 + rel));
    Hit h;
    bool hit = s->intersect(Ray{Point3(b, 0, 100), Vec3(0, 0, -1)}, h);
    if (hit) {
      EXPECT_TRUE(std::isfinite(h.t) && isFinite(h.p) && isFinite(h.ng)) << rel;
      EXPECT_NEAR(h.t, 100.0f, 0.5f) << rel;
    }
    if (rel <= -1e-5) {
      EXPECT_TRUE(hit) << "just inside the silhouette must hit: " << rel;
    }
    if (rel >= 1e-5) {
      EXPECT_FALSE(hit) << "just outside must miss: " << rel;
    }
    FieldSample f = queryRay(*s, Point3(b, 0, 100), Vec3(0, 0, -1), l);
    EXPECT_TRUE(allFinite(f.L)) << rel;
    EXPECT_GE(f.L[0], 0.0f);
  }
}

TEST(Shapes, RayAlongBoxEdgeNoNaN) {
  auto s = sceneFromString(R"({
    "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
    "objects": [{"type": "box", "size_mm": [10, 10, 10], "material": "m"}],
    "lights": [{"type": "point", "position_mm": [3, 40, 50], "spectrum": 100},
               {"type": "environment", "spectrum": 0.2}]
  })");
  SampledWavelengths l = wavelengthsAt(500);
  const Ray rays[] = {
      {Point3(5, 5, 100), Vec3(0, 0, -1)},     // down a vertical edge
      {Point3(-100, 5, 5), Vec3(1, 0, 0)},     // along a top edge
      {Point3(-100, 5, 0), Vec3(1, 0, 0)},     // in the plane of a face
      {Point3(100, 100, 100), glm::normalize(Vec3(-1, -1, -1))},  // at a corner
      {Point3(0, 0, 0), Vec3(1, 0, 0)},        // from inside
  };
  for (const Ray& r : rays) {
    Hit h;
    if (s->intersect(r, h)) {
      EXPECT_TRUE(std::isfinite(h.t) && isFinite(h.p) && isFinite(h.ng));
      EXPECT_NEAR(glm::length(h.ng), 1.0f, 1e-5f);
    }
    for (uint32_t k = 0; k < 16; ++k) {
      FieldSample f = queryRay(*s, r.o, r.d, l, 3, k);
      EXPECT_TRUE(allFinite(f.L));
    }
  }
  // The corner ray must hit the corner region at distance |(95,95,95)| * ... = 95 sqrt(3).
  Hit h;
  ASSERT_TRUE(s->intersect(rays[3], h));
  EXPECT_NEAR(h.t, 95.0f * std::sqrt(3.0f), 1e-3f);
}

TEST(Shapes, DegenerateTrianglesSkipped) {
  std::string dir = scratchDir();
  writeFile(dir, "degenerate.obj",
            "# one good triangle, a zero-area one (repeated vertex) and a collinear one\n"
            "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 20 0 0\nv 5 5 0\n"
            "f 1 2 3\nf 1 1 2\nf 1 2 4\nf 2 5 3\n");
  writeFile(dir, "all-degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  std::string scene = R"({
    "materials": {"m": {"type": "diffuse"}},
    "objects": [{"type": "mesh", "file": "FILE", "material": "m"}],
    "lights": [{"type": "point", "position_mm": [2, 2, 30], "spectrum": 100}]})";
  std::string good = scene;
  good.replace(good.find("FILE"), 4, "degenerate.obj");
  auto s = sceneFromString(good, dir + "/scene.json");
  EXPECT_EQ(s->droppedTriangles(), 3u);  // 1 1 2, 1 2 4 (collinear), 2 5 3 (collinear)
  SampledWavelengths l = wavelengthsAt(550);
  FieldSample f = queryRay(*s, Point3(2, 2, 50), Vec3(0, 0, -1), l);
  EXPECT_FLOAT_EQ(f.depth, 50.0f);
  EXPECT_TRUE(allFinite(f.L));
  EXPECT_GT(f.L[0], 0.0f);
  // Rays at the degenerate triangles' places see nothing and stay finite.
  FieldSample g = queryRay(*s, Point3(15, 0, 50), Vec3(0, 0, -1), l);
  EXPECT_TRUE(allFinite(g.L));
  EXPECT_EQ(g.opacity, 0.0f);
  std::string bad = scene;
  bad.replace(bad.find("FILE"), 4, "all-degenerate.obj");
  EXPECT_THROW(sceneFromString(bad, dir + "/scene.json"), InputError);
}

// Direct lighting of a Lambertian plane by a point light at any scale: exact value, and
// correct hit distances. Self-shadowing (a too small ray offset) would give 0; a too large
// offset would make the thin box below leak. Both scales must match the analytic value.
TEST(Shapes, MicrometreAndMetreScales) {
  for (double scale : {1e-3, 1.0, 1e4}) {
    Json j = Json::parse(R"({"materials": {"w": {"type": "diffuse", "reflectance": 0.5}}})");
    j["objects"] = Json::array();
    j["objects"].push_back({{"type", "sphere"}, {"radius_mm", 1.0 * scale},
                            {"translate_mm", {0.0, 0.0, -2.0 * scale}}, {"material", "w"}});
    j["objects"].push_back({{"type", "box"}, {"size_mm", {10.0 * scale, 10.0 * scale, 0.5 * scale}},
                            {"translate_mm", {20.0 * scale, 0.0, -0.25 * scale}}, {"material", "w"}});
    // Intensity scale^2 keeps the radiance scale-free.
    j["lights"] = Json::array();
    j["lights"].push_back({{"type", "point"}, {"position_mm", {23.0 * scale, 0.0, 4.0 * scale}},
                           {"spectrum", scale * scale}});
    auto s = AnalyticScene::fromJson(j, "scale-test.json");
    SampledWavelengths l = wavelengthsAt(550);
    // Sphere: hit distance 10 + 2 - 1 (x scale) from z = 10 scale.
    FieldSample f = queryRay(*s, Point3(0, 0, float(10 * scale)), Vec3(0, 0, -1), l);
    EXPECT_NEAR(f.depth, 11.0 * scale, 1e-4 * 11.0 * scale) << scale;
    EXPECT_TRUE(allFinite(f.L));
    // Top of the box at z = 0, lit from (3, 0, 4) * scale relative to the hit point.
    Point3 o(float(20 * scale), 0.0f, float(10 * scale));
    FieldSample g = queryRay(*s, o, Vec3(0, 0, -1), l);
    EXPECT_NEAR(g.depth, 10.0 * scale, 1e-4 * 10.0 * scale) << scale;
    double r2 = 25.0 * scale * scale, cosT = 4.0 / 5.0;
    double expected = 0.5 / M_PI * (scale * scale) * cosT / r2;
    EXPECT_NEAR(g.L[0], expected, 1e-4 * expected) << "scale " << scale;
  }
}

TEST(Shapes, AreaSamplingPdfIntegratesToOne) {
  // Sampling an emissive ellipsoid uniformly in object space: mean of 1/pdf = its area.
  Shape s;
  s.type = ShapeType::Sphere;
  s.radius = 1.0;
  s.setTransform(Transform::scale({2, 2, 2}));
  s.finalize();
  double sum = 0;
  int n = 20000;
  Rng rng(1, 2);
  for (int i = 0; i < n; ++i) {
    ShapeSample ss = sampleShapeArea(s, Vec2(rng.uniform(), rng.uniform()), rng.uniform());
    sum += 1.0 / ss.pdfArea;
    EXPECT_NEAR(glm::length(ss.p), 2.0f, 1e-5f);
  }
  EXPECT_NEAR(sum / n, 4 * M_PI * 4.0, 1e-3 * 4 * M_PI * 4.0);
}

TEST(ObjLoader, ParsesFacesAndRejectsBadIndices) {
  ObjMesh m = parseObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                       "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n", "quad.obj");
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_EQ(m.P.size(), 4u);
  EXPECT_EQ(m.N.size(), 4u);
  EXPECT_EQ(m.UV.size(), 4u);
  ObjMesh neg = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", "neg.obj");
  EXPECT_EQ(neg.indices.size(), 3u);
  try {
    parseObj("v 0 0 0\nf 1 2 3\n", "bad.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos);
  }
}
