// Bad input gets an InputError naming the file, the key path and the bad value; good input
// (the shipped scenes) loads.
#include <gtest/gtest.h>

#include "core/image.h"
#include "core/output_file.h"
#include "scene_test_util.h"

using namespace inim;
using namespace inim::test;

namespace {
const char* kBase = R"({
  "materials": {"white": {"type": "diffuse", "reflectance": 0.8}},
  "objects": [OBJ],
  "lights": [{"type": "point", "position_mm": [0, 0, 100], "spectrum": 100}]})";

std::string withObject(const std::string& obj) {
  std::string s = kBase;
  s.replace(s.find("OBJ"), 3, obj);
  return s;
}

// Loads `text` from a file and returns the InputError message (fails if none is thrown).
std::string loadError(const std::string& text, const std::string& name = "scene.json") {
  std::string dir = scratchDir();
  std::string path = writeFile(dir, name, text);
  try {
    AnalyticScene::load(path);
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(name), std::string::npos) << "message must name the file: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return "";
}

void expectContains(const std::string& msg, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}
}  // namespace

TEST(SceneLoader, MalformedJson) {
  std::string msg = loadError("{ \"objects\": [ {\"type\": \"sphere\", } ");
  expectContains(msg, {"malformed JSON"});
}

TEST(SceneLoader, UnknownTopLevelKey) {
  expectContains(loadError(R"({"objectz": []})"), {"objectz", "known keys"});
}

TEST(SceneLoader, MisspeltObjectKey) {
  std::string msg = loadError(withObject(
      R"({"type": "sphere", "radius_mm": 5, "material": "white", "translate_m": [0, 0, 1]})"));
  expectContains(msg, {"objects[0].translate_m", "[0,0,1]", "translate_mm"});
}

TEST(SceneLoader, MisspeltMaterialKey) {
  std::string msg = loadError(R"({"materials": {"w": {"type": "diffuse", "reflectanse": 0.5}}})");
  expectContains(msg, {"materials.w.reflectanse", "0.5"});
}

TEST(SceneLoader, ZeroAndNegativeSizes) {
  expectContains(loadError(withObject(R"({"type": "box", "size_mm": [1, 0, 1], "material": "white"})")),
                 {"objects[0].size_mm", "[1,0,1]", "> 0"});
  expectContains(loadError(withObject(R"({"type": "sphere", "radius_mm": -2, "material": "white"})")),
                 {"objects[0].radius_mm", "-2", "> 0"});
  expectContains(loadError(withObject(R"({"type": "cylinder", "radius_mm": 2, "height_mm": 0, "material": "white"})")),
                 {"objects[0].height_mm", "0"});
  expectContains(loadError(withObject(R"({"type": "sphere", "radius_mm": 2, "scale": [1, 0, 1], "material": "white"})")),
                 {"objects[0].scale", "[1,0,1]"});
  expectContains(loadError(R"({"lights": [{"type": "rect", "size_mm": [10, -1], "position_mm": [0,0,1], "look_at_mm": [0,0,0]}]})"),
                 {"lights[0].size_mm", "[10,-1]"});
}

TEST(SceneLoader, DuplicateIds) {
  expectContains(loadError(withObject(R"({"id": 3, "name": "a", "type": "sphere", "radius_mm": 1, "material": "white"},
                                         {"id": 3, "name": "b", "type": "sphere", "radius_mm": 1, "material": "white"})")),
                 {"objects[1].id", "3", "\"a\""});
}

TEST(SceneLoader, UnknownMaterialListsKnownOnes) {
  std::string msg = loadError(withObject(R"({"type": "sphere", "radius_mm": 5, "material": "gold"})"));
  expectContains(msg, {"objects[0].material", "\"gold\"", "known: white"});
}

TEST(SceneLoader, UnknownCatalogNames) {
  expectContains(loadError(R"({"materials": {"g": {"type": "dielectric", "ior": "N-BK8"}}})"),
                 {"materials.g.ior", "N-BK8", "N-BK7"});
  expectContains(loadError(R"({"materials": {"c": {"type": "conductor", "metal": "Bronze"}}})"),
                 {"materials.c.metal", "Bronze", "Cu"});
}

TEST(SceneLoader, MissingFilesNameFileAndKey) {
  expectContains(loadError(withObject(R"({"type": "mesh", "file": "nope.obj", "material": "white"})")),
                 {"objects[0].file", "nope.obj"});
  expectContains(
      loadError(R"({"materials": {"w": {"type": "diffuse", "reflectance": {"type": "csv", "file": "missing.csv"}}}})"),
      {"materials.w.reflectance.file", "missing.csv"});
  expectContains(
      loadError(R"({"materials": {"w": {"type": "diffuse", "reflectance": {"type": "image", "file": "missing.png"}}}})"),
      {"materials.w.reflectance.file", "missing.png"});
}

TEST(SceneLoader, OutOfRangeSpectraAndChoices) {
  expectContains(loadError(R"({"materials": {"w": {"type": "diffuse", "reflectance": 1.5}}})"),
                 {"materials.w.reflectance", "1.5", "[0, 1]"});
  expectContains(loadError(R"({"materials": {"w": {"type": "glass"}}})"),
                 {"materials.w.type", "glass", "dielectric"});
  expectContains(loadError(R"({"integrator": {"type": "bidir"}})"), {"integrator.type", "bidir", "path"});
  expectContains(loadError(R"({"units": "cm"})"), {"units", "cm", "mm"});
}

TEST(SceneLoader, EmptySceneIsBlack) {
  auto s = sceneFromString("{}");
  FieldSample f = queryRay(*s, Point3(0, 0, 10), Vec3(0, 0, -1), wavelengthsAt(500));
  for (int i = 0; i < kNumWavelengths; ++i) EXPECT_EQ(f.L[i], 0.0f);
  EXPECT_EQ(f.opacity, 0.0f);
  EXPECT_TRUE(std::isinf(f.depth));
  Point3 lo, hi;
  s->bounds(lo, hi);
  EXPECT_TRUE(isFinite(lo) && isFinite(hi));
  // The batched path too.
  std::vector<FieldRay> rays(100);
  std::vector<SampledWavelengths> lam(100, wavelengthsAt(500));
  std::vector<FieldSample> out(100);
  for (size_t i = 0; i < rays.size(); ++i) rays[i].d = glm::normalize(Vec3(float(i) - 50.0f, 1.0f, -3.0f));
  s->query(rays, lam, out, 1);
  for (const FieldSample& o : out) {
    EXPECT_EQ(o.L[0], 0.0f);
    EXPECT_EQ(o.opacity, 0.0f);
  }
  // Lights but no objects: nothing to light, nothing crashes.
  auto t = sceneFromString(R"({"lights": [{"type": "point", "position_mm": [0, 0, 5], "spectrum": 1}]})");
  EXPECT_EQ(queryRay(*t, Point3(0), Vec3(1, 0, 0), wavelengthsAt(500)).L[0], 0.0f);
}

TEST(SceneLoader, TexturesSpectraAndMeshesLoad) {
  std::string dir = scratchDir();
  writeFile(dir, "refl.csv", "# test reflectance\nwavelength_nm,r\n360,0.1\n830,0.9\n");
  writeFile(dir, "tri.obj", "v -10 -10 0\nv 10 -10 0\nv 0 10 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n");
  Image img(2, 2, {"R", "G", "B"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) img.at(x, y, (x + y) % 3) = 1.0f;
  writeImage(img, dir + "/tex.png");
  std::string path = writeFile(dir, "scene.json", R"({
    "materials": {
      "csv": {"type": "diffuse", "reflectance": {"type": "csv", "file": "refl.csv", "column": "r"}},
      "img": {"type": "diffuse", "reflectance": {"type": "image", "file": "tex.png"}},
      "chk": {"type": "diffuse", "reflectance": {"type": "checker", "period_mm": 2, "background": [0.9, 0.9, 0.8], "ink": 0.05}},
      "gauss": {"type": "diffuse", "reflectance": {"type": "gaussian", "mean_nm": 530, "fwhm_nm": 40, "peak": 0.8, "base": 0.05}},
      "warm": {"type": "emitter", "spectrum": {"type": "blackbody", "temperature_k": 3200}, "scale": 5},
      "gold": {"type": "conductor", "metal": "Au", "roughness": 0.2}
    },
    "objects": [
      {"id": 1, "name": "csv", "type": "rectangle", "size_mm": [10, 10], "material": "csv"},
      {"id": 2, "name": "img", "type": "rectangle", "size_mm": [10, 10], "translate_mm": [20, 0, 0], "material": "img"},
      {"id": 3, "name": "chk", "type": "box", "size_mm": [10, 10, 10], "translate_mm": [40, 0, -5], "material": "chk"},
      {"id": 4, "name": "tri", "type": "mesh", "file": "tri.obj", "translate_mm": [60, 0, 0], "material": "gauss"},
      {"id": 5, "name": "lamp", "type": "sphere", "radius_mm": 3, "translate_mm": [0, 40, 20], "material": "warm"},
      {"id": 6, "name": "ring", "type": "cylinder", "radius_mm": 5, "height_mm": 1, "caps": false, "translate_mm": [80, 0, 0], "material": "gold"}
    ],
    "lights": [{"type": "rect", "size_mm": [50, 50], "position_mm": [30, 0, 100], "look_at_mm": [30, 0, 0], "spectrum": "D65", "scale": 3},
               {"type": "environment", "spectrum": {"type": "rgb", "rgb": [0.1, 0.1, 0.2]}}]})");
  auto s = AnalyticScene::load(path, IntegratorSettings{IntegratorSettings::Type::Path, 5});
  EXPECT_EQ(s->objects().size(), 6u);
  EXPECT_EQ(s->lights().lights().size(), 3u);  // rect, environment, emissive sphere
  ASSERT_NE(s->objectById(4), nullptr);
  EXPECT_EQ(s->objectById(4)->material, "gauss");
  for (float x : {0.0f, 20.0f, 40.0f, 60.0f, 80.0f}) {
    MeanEstimate e = averageRay(*s, Point3(x, 0, 50), Vec3(0, 0, -1), wavelengthsAt(560), 64);
    for (int i = 0; i < kNumWavelengths; ++i) {
      EXPECT_TRUE(std::isfinite(e.mean[i]));
      EXPECT_GE(e.mean[i], 0.0);
    }
    EXPECT_GT(e.mean[0] + e.mean[1] + e.mean[2] + e.mean[3], 0.0) << x;
  }
}

TEST(SceneLoader, ShippedTestScenesLoad) {
  for (const char* f : {"scenes/test/point-sphere.json", "scenes/test/slanted-edge.json",
                        "scenes/test/furnace.json", "scenes/paper-fig7.json"}) {
    auto s = AnalyticScene::load(dataPath(f));
    EXPECT_FALSE(s->objects().empty()) << f;
    EXPECT_EQ(s->droppedTriangles(), 0u) << f;
  }
}

// The shipped test scenes do what scenes/README.md says they do.
TEST(SceneLoader, ShippedTestScenesBehaveAsDocumented) {
  const Point3 cam(0, 0, 350);
  SampledWavelengths l = wavelengthsAt(530);
  {
    auto s = AnalyticScene::load(dataPath("scenes/test/point-sphere.json"));
    FieldSample f = queryRay(*s, cam, Vec3(0, 0, -1), l);
    EXPECT_NEAR(f.depth, 350.0f + 10.0f - 0.25f, 1e-4f);
    EXPECT_GT(f.L[0], 0.0f);
    EXPECT_EQ(queryRay(*s, cam, Vec3(0.01f, 0, -1), l).opacity, 0.0f);
  }
  {
    auto s = AnalyticScene::load(dataPath("scenes/test/slanted-edge.json"));
    // Paper and ink of the edge target at z = 0 (edge through its centre (0, 14)).
    FieldSample paper = queryRay(*s, cam, Point3(6, 14, 0) - cam, l);
    FieldSample ink = queryRay(*s, cam, Point3(-6, 14, 0) - cam, l);
    for (int i = 0; i < kNumWavelengths; ++i) {
      EXPECT_NEAR(paper.L[i], 0.8f, 1e-5f);
      EXPECT_NEAR(ink.L[i], 0.05f, 1e-6f);
    }
    FieldSample back = queryRay(*s, cam, Point3(50, 14, 20) + Vec3(6, 0, 0) - cam, l);
    EXPECT_NEAR(back.L[0], 0.8f * std::pow(1e6f / (1e6f - 20.0f), 2.0f), 1e-5f);
  }
  {
    auto s = AnalyticScene::load(dataPath("scenes/test/furnace.json"));
    for (float x : {-30.0f, -45.0f, 20.0f})
      for (int i = 0; i < kNumWavelengths; ++i)
        EXPECT_NEAR(queryRay(*s, cam, Point3(x, 3, 0) - cam, l, 1, uint32_t(x + 100)).L[i], 1.0f, 1e-5f);
  }
}
