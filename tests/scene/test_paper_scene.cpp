// The analytic stand-in for the paper's Fig. 7: its ingredients are where the paper puts
// them, and the filter and the coin do what they are there for.
#include <gtest/gtest.h>

#include <fstream>

#include "scene_test_util.h"

using namespace inim;
using namespace inim::test;

namespace {
const Point3 kCamera(0, 0, 350);

Json fig7Json() {
  std::ifstream in(dataPath("scenes/paper-fig7.json"));
  return Json::parse(in, nullptr, true, true);
}
std::string fig7File() { return dataPath("scenes/paper-fig7.json"); }
}  // namespace

TEST(PaperScene, LoadsWithEightNumberedObjects) {
  auto s = AnalyticScene::load(fig7File());
  EXPECT_GE(s->objects().size(), 8u);
  for (int id = 1; id <= 8; ++id) ASSERT_NE(s->objectById(id), nullptr) << "object " << id;
  // The frame: content spans the panel's 152 x 65 mm front view (and the backdrop more).
  Point3 lo, hi;
  s->bounds(lo, hi);
  EXPECT_LT(lo.x, -76.0f);
  EXPECT_GT(hi.x, 76.0f);
  EXPECT_LT(lo.y, -32.5f);
  EXPECT_GT(hi.y, 32.5f);
  // Objects in front of and behind the MLA plane.
  int front = 0, behind = 0;
  for (int id = 1; id <= 8; ++id) {
    const Shape& sh = s->geometry().shape(s->objectById(id)->shape);
    float zc = 0.5f * (sh.lo.z + sh.hi.z);
    front += zc > 1.0f;
    behind += zc < -1.0f;
  }
  EXPECT_GE(front, 2);
  EXPECT_GE(behind, 2);
}

TEST(PaperScene, ScaleTargetLiesOnMlaPlane) {
  auto s = AnalyticScene::load(fig7File());
  const SceneObject* o3 = s->objectById(3);
  ASSERT_NE(o3, nullptr);
  const Shape& sh = s->geometry().shape(o3->shape);
  ASSERT_EQ(sh.type, ShapeType::Mesh);
  for (const Vec3& p : sh.P) EXPECT_EQ(p.z, 0.0f);
  // A ray to its centre meets it at z = 0, i.e. at distance 350 along the axis.
  Point3 c = 0.5f * (sh.lo + sh.hi);
  Hit h;
  ASSERT_TRUE(s->intersect(Ray{kCamera, glm::normalize(c - kCamera)}, h));
  EXPECT_EQ(h.shape, o3->shape);
  EXPECT_NEAR(h.p.z, 0.0f, 1e-4f);
  // It is printed: ink and paper both appear along a line through the rulers.
  const Material& m = s->materials()[sh.material];
  SampledWavelengths l = wavelengthsAt(550);
  float mn = 1, mx = 0;
  for (float x = -30; x <= 30; x += 0.1f) {
    SurfaceCoords tc;
    tc.st = Vec2(x, 12.0f);  // in the top ruler band
    float r = m.reflectance.evaluate(tc, l)[0];
    mn = std::min(mn, r);
    mx = std::max(mx, r);
  }
  EXPECT_LT(mn, 0.1f);
  EXPECT_GT(mx, 0.8f);
}

// The yellow filter: blue is absorbed, yellow/red pass. Compare the same ray with the
// filter and with the filter removed from the scene.
TEST(PaperScene, FilterShiftsTowardYellow) {
  Json with = fig7Json(), without = fig7Json();
  auto& objs = without["objects"];
  for (size_t i = 0; i < objs.size(); ++i)
    if (objs[i]["id"] == 6) {
      objs.erase(i);
      break;
    }
  auto a = AnalyticScene::fromJson(with, fig7File());
  auto b = AnalyticScene::fromJson(without, fig7File());
  const Material& filter = a->materials()[a->geometry().shape(a->objectById(6)->shape).material];
  ASSERT_EQ(filter.type, MaterialType::ThinDielectric);
  EXPECT_LT(filter.tau(450.0f), 0.1f * filter.tau(600.0f));

  Point3 target(-2, -22, 14);  // on the filter, with the backdrop behind it
  Vec3 d = target - kCamera;
  SampledWavelengths l = wavelengthsAt(450);  // 450, 567.5, 685, 802.5 nm
  Hit h;
  ASSERT_TRUE(a->intersect(Ray{kCamera, glm::normalize(d)}, h));
  EXPECT_EQ(h.shape, a->objectById(6)->shape);
  MeanEstimate ea = averageRay(*a, kCamera, d, l, 3000);
  MeanEstimate eb = averageRay(*b, kCamera, d, l, 3000);
  double blueYellowWith = ea.mean[0] / ea.mean[1], blueYellowWithout = eb.mean[0] / eb.mean[1];
  EXPECT_LT(blueYellowWith, 0.2 * blueYellowWithout);
  EXPECT_GT(ea.mean[1], 0.3 * eb.mean[1]);  // yellow still passes (two passes of ~0.9 T)
  RecordProperty("blue_to_yellow_with_filter", std::to_string(blueYellowWith));
  RecordProperty("blue_to_yellow_without_filter", std::to_string(blueYellowWithout));
}

TEST(PaperScene, CoinReflects) {
  auto s = AnalyticScene::load(fig7File());
  const SceneObject* coin = s->objectById(7);
  ASSERT_NE(coin, nullptr);
  const Shape& sh = s->geometry().shape(coin->shape);
  EXPECT_EQ(sh.type, ShapeType::Cylinder);
  EXPECT_EQ(s->materials()[sh.material].type, MaterialType::Conductor);
  Point3 c = Point3(sh.T);
  Hit h;
  ASSERT_TRUE(s->intersect(Ray{kCamera, glm::normalize(c - kCamera)}, h));
  EXPECT_EQ(h.shape, coin->shape);
  MeanEstimate e = averageRay(*s, kCamera, c - kCamera, wavelengthsAt(600), 500);
  for (int i = 0; i < kNumWavelengths; ++i) EXPECT_TRUE(std::isfinite(e.mean[i]));
  EXPECT_GT(e.mean[0], 0.05);  // a mirror image of lit objects, not black
}

// The batched (wavefront) query returns exactly what the one-ray query returns.
TEST(PaperScene, BatchedQueryEqualsSingleRayQuery) {
  auto s = AnalyticScene::load(fig7File());
  const int n = 2000;
  std::vector<FieldRay> rays(n);
  std::vector<SampledWavelengths> lam(n);
  std::vector<FieldSample> out(n);
  Rng rng(3, 4);
  for (int i = 0; i < n; ++i) {
    rays[i].o = kCamera;
    rays[i].d = glm::normalize(Vec3(rng.uniform() * 160 - 80, rng.uniform() * 70 - 35, -350));
    rays[i].id = uint64_t(i);
    lam[i] = SampledWavelengths::sampleVisible(rng.uniform());
  }
  rays[7].d = Vec3(0.0f);         // degenerate: sees nothing
  rays[8].tNear = 1000.0f;        // clipped beyond everything
  s->query(rays, lam, out, 9);
  for (int i = 0; i < n; ++i) {
    FieldSample one = s->queryOne(rays[i], lam[i], 9);
    for (int k = 0; k < kNumWavelengths; ++k) ASSERT_EQ(out[i].L[k], one.L[k]) << i;
    ASSERT_EQ(out[i].depth, one.depth) << i;
    ASSERT_EQ(out[i].opacity, one.opacity) << i;
  }
  EXPECT_EQ(out[7].opacity, 0.0f);
  EXPECT_EQ(out[8].opacity, 0.0f);
}
