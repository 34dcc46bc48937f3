// A dataset meets a radiance field: training rays through the pixel centres (lens distortion
// removed), held-out frames kept out of training and scored, the scores of a field that
// reproduces the photos exactly or with a known error, and the model's default placement.
#include "fitting/dataset_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/dataset_test_util.h"
#include "fixtures.h"

using namespace inim;
using fixtures::expectInputError;

namespace {

constexpr int kSize = 12;  // image side: SSIM's 11 x 11 window fits

// Pixel (x, y, channel) of frame i of the in-memory dataset: distinct values on a 1/16 grid.
float patternValue(int frame, int x, int y, int channel) {
  return float((7 * x + 13 * y + 3 * channel + 5 * frame) % 17) / 16.0f;
}

// `frames` kSize x kSize cameras on the dataset tests' ring (radius 4, looking at the origin)
// with a distorted lens, holding the pattern above (or one grey value when grey >= 0), every
// `holdoutEvery`-th frame held out.
Dataset inMemoryDataset(int frames, float grey = -1.0f, int holdoutEvery = 8) {
  Dataset d;
  d.file = "(in memory)";
  d.format = "blender";
  d.nearPlane = 1.0;
  d.farPlane = 7.0;
  const auto poses = dataset_test::ringPoses(frames);
  for (int i = 0; i < frames; ++i) {
    DatasetFrame f;
    f.imagePath = "frame_" + std::to_string(i) + ".png";
    f.sourceIndex = i;
    f.intrinsics.width = f.intrinsics.height = kSize;
    f.intrinsics.fx = 14.0;
    f.intrinsics.fy = 15.0;
    f.intrinsics.cx = 6.25;
    f.intrinsics.cy = 5.75;
    f.intrinsics.k1 = -0.08;
    f.intrinsics.k2 = 0.01;
    f.intrinsics.p1 = 0.002;
    f.intrinsics.p2 = -0.001;
    f.cameraToWorld = poses[size_t(i)];
    f.image = Image(kSize, kSize, {"R", "G", "B"});
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int c = 0; c < 3; ++c) f.image.at(x, y, c) = grey >= 0.0f ? grey : patternValue(i, x, y, c);
    d.frames.push_back(f);
  }
  splitTrainTest(frames, holdoutEvery, d.train, d.test);
  return d;
}

// A field with no density anywhere: every ray sees the background colour.
VoxelGrid emptyField(const Vec3& background) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(5), 0, DensityActivation::ReLU,
                                  background, 0.01f);
  for (float& raw : g.density) raw = -1.0f;  // ReLU: sigma = 0
  return g;
}

// SSIM of two uniform grey images a and b (their local variances are 0): the luminance term
// (2 a b + C1) / (a^2 + b^2 + C1), C1 = (0.01 * 1)^2.
double uniformSsim(double a, double b) {
  const double c1 = 1e-4;
  return (2.0 * a * b + c1) / (a * a + b * b + c1);
}

}  // namespace

// One ray per pixel centre, frames in the order asked, pixels row by row: it starts at the
// camera, is unit length, projects back (through the lens distortion) onto its pixel centre,
// and carries that pixel's value and the dataset's near/far.
TEST(TrainingRays, OnePerPixelCentreThroughTheDistortedLens) {
  const Dataset data = inMemoryDataset(3);
  const std::vector<int> frames{2, 0};
  const TrainingRays rays = datasetRays(data, frames);
  const size_t perFrame = size_t(kSize) * kSize;
  ASSERT_EQ(rays.size(), frames.size() * perFrame);
  ASSERT_EQ(rays.dir.size(), rays.size());
  ASSERT_EQ(rays.rgb.size(), rays.size());
  ASSERT_EQ(rays.tNear.size(), rays.size());
  ASSERT_EQ(rays.tFar.size(), rays.size());
  for (size_t r = 0; r < rays.size(); ++r) {
    const int frame = frames[r / perFrame];
    const DatasetFrame& f = data.frames[size_t(frame)];
    const int x = int(r % perFrame) % kSize, y = int(r % perFrame) / kSize;
    EXPECT_NEAR(glm::length(glm::dvec3(rays.origin[r]) - f.position()), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(rays.dir[r]), 1.0f, 1e-6f);
    glm::dvec2 pixel;
    ASSERT_TRUE(projectToFrame(f, glm::dvec3(rays.origin[r]) + 3.0 * glm::dvec3(rays.dir[r]), pixel));
    EXPECT_NEAR(pixel.x, x + 0.5, 1e-6) << "ray " << r;
    EXPECT_NEAR(pixel.y, y + 0.5, 1e-6) << "ray " << r;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rays.rgb[r][c], patternValue(frame, x, y, c));
    EXPECT_EQ(rays.tNear[r], 1.0f);
    EXPECT_EQ(rays.tFar[r], 7.0f);
  }
  // The distortion matters: the corner ray is not the pinhole ray through the corner pixel.
  DatasetFrame pinhole = data.frames[2];
  pinhole.intrinsics.k1 = pinhole.intrinsics.k2 = pinhole.intrinsics.p1 = pinhole.intrinsics.p2 = 0.0;
  glm::dvec3 o, d;
  frameRay(pinhole, 0.5, 0.5, o, d);
  EXPECT_GT(glm::length(d - glm::dvec3(rays.dir[0])), 1e-3);
}

// A dataset read from disk with every 4th frame held out: the training rays come from the
// other frames only (their cameras, kSize^2 rays each), and evaluation scores exactly the
// held-out frames. A field that reproduces the photos (here: a grey background equal to the
// photos' grey) scores PSNR = +inf and SSIM = 1 on each.
TEST(HeldOut, EveryFourthFrameIsScoredAndNeverTrainedOn) {
  const std::string dir = dataset_test::blenderDataset("fitting_split", 10, kSize, {0.2f, 0.4f, 0.6f});
  DatasetOptions options;
  options.holdoutEvery = 4;
  const Dataset data = loadDataset(dir, options);
  ASSERT_EQ(data.frames.size(), 10u);
  ASSERT_EQ(data.test, (std::vector<int>{0, 4, 8}));

  const TrainingRays rays = datasetRays(data, data.train);
  const size_t perFrame = size_t(kSize) * kSize;
  ASSERT_EQ(rays.size(), data.train.size() * perFrame);
  for (size_t t = 0; t < data.train.size(); ++t) {
    const glm::dvec3 camera = data.frames[size_t(data.train[t])].position();
    for (size_t p = 0; p < perFrame; p += 37)
      EXPECT_NEAR(glm::length(glm::dvec3(rays.origin[t * perFrame + p]) - camera), 0.0, 1e-6);
  }
  for (int held : data.test)
    for (size_t r = 0; r < rays.size(); r += 11)
      EXPECT_GT(glm::length(glm::dvec3(rays.origin[r]) - data.frames[size_t(held)].position()), 0.1);

  const Image& photo = data.frames[0].image;
  const VoxelGrid field = emptyField(Vec3(photo.at(0, 0, 0), photo.at(0, 0, 1), photo.at(0, 0, 2)));
  std::vector<Image> renders;
  const std::vector<ViewScore> scores = evaluate(field, data, data.test, &renders);
  ASSERT_EQ(scores.size(), 3u);
  ASSERT_EQ(renders.size(), 3u);
  for (size_t i = 0; i < scores.size(); ++i) {
    const DatasetFrame& f = data.frames[size_t(data.test[i])];
    EXPECT_EQ(scores[i].frame, data.test[i]);
    EXPECT_EQ(scores[i].image, f.imagePath);
    EXPECT_TRUE(std::isinf(scores[i].psnr) && scores[i].psnr > 0.0) << scores[i].psnr;
    EXPECT_NEAR(scores[i].ssim, 1.0, 1e-12);
    EXPECT_EQ(renders[i].data, f.image.data);
  }
}

// A uniform error of 1/8 on photos of grey 1/4: PSNR = 20 log10(8) dB and SSIM the luminance
// term of two uniform images. Renders are clamped to [0, 1] like the photos: a background
// of 1.5 scores as 1.
TEST(Evaluate, UniformErrorGivesTheAnalyticPsnrAndSsim) {
  const Dataset data = inMemoryDataset(2, 0.25f);
  const std::vector<ViewScore> off = evaluate(emptyField(Vec3(0.375f)), data, {0, 1}, nullptr);
  ASSERT_EQ(off.size(), 2u);
  for (const ViewScore& s : off) {
    EXPECT_NEAR(s.psnr, 20.0 * std::log10(8.0), 1e-9);
    EXPECT_NEAR(s.ssim, uniformSsim(0.25, 0.375), 1e-9);
  }
  std::vector<Image> renders;
  const std::vector<ViewScore> clamped = evaluate(emptyField(Vec3(1.5f)), data, {1}, &renders);
  ASSERT_EQ(renders.size(), 1u);
  for (float v : renders[0].data) ASSERT_EQ(v, 1.0f);
  EXPECT_NEAR(clamped[0].psnr, 20.0 * std::log10(1.0 / 0.75), 1e-9);
  EXPECT_NEAR(clamped[0].ssim, uniformSsim(0.25, 1.0), 1e-9);
}

// Frames loaded without their pixels cannot be scored.
TEST(Evaluate, FramesWithoutPixelsAreAnInputError) {
  const std::string dir = dataset_test::blenderDataset("fitting_no_pixels", 3, kSize, {0.5f, 0.5f, 0.5f});
  DatasetOptions options;
  options.loadImages = false;
  const Dataset data = loadDataset(dir, options);
  ASSERT_FALSE(data.test.empty());
  expectInputError([&] { evaluate(emptyField(Vec3(0.5f)), data, data.test, nullptr); });
}

// An inim capture (its transforms.json records "inim_capture": {"units": "mm", ...}) is in
// millimetres: the model is placed at scale 1 and keeps the capture's scene. Any other
// dataset is in its own units, placed at the paper's 0.0075 field units per mm (a point
// 0.0075 units from the origin lands 1 mm from it). Metadata that is not JSON counts as
// "dataset units".
TEST(Placement, DefaultFollowsTheDatasetUnits) {
  const std::string dir =
      dataset_test::blenderDataset("fitting_capture", 2, 4, {0.5f, 0.5f, 0.5f}, "transforms.json");
  nlohmann::json transforms = nlohmann::json::parse(fixtures::readBytes(dir + "/transforms.json"));
  const nlohmann::json plain = transforms;
  transforms["inim_capture"] = {{"units", "mm"}, {"scene", "scenes/test/point-sphere.json"}};
  fixtures::writeBytes(dir + "/transforms.json", transforms.dump());
  const Dataset capture = loadDataset(dir);
  const nlohmann::json meta = nlohmann::json::parse(modelMetadata(capture));
  EXPECT_EQ(meta["dataset"], capture.file);
  EXPECT_EQ(meta["format"], "blender");
  EXPECT_EQ(meta["units"], "mm");
  EXPECT_EQ(meta["scene"], "scenes/test/point-sphere.json");
  const Placement mm = defaultPlacementFor(meta.dump());
  EXPECT_EQ(mm.scale, Vec3d(1.0));
  EXPECT_TRUE(mm.isIdentity());
  EXPECT_EQ(mm.scaleKey, "scale");

  fixtures::writeBytes(dir + "/transforms.json", plain.dump());
  const Dataset foreign = loadDataset(dir);
  const nlohmann::json foreignMeta = nlohmann::json::parse(modelMetadata(foreign));
  EXPECT_EQ(foreignMeta["units"], "dataset");
  EXPECT_FALSE(foreignMeta.contains("scene"));
  const Placement own = defaultPlacementFor(foreignMeta.dump());
  const Point3d landed = own.toDisplay().point(Point3d(0.0075, 0.0, -0.0075));
  EXPECT_NEAR(landed.x, 1.0, 1e-12);
  EXPECT_NEAR(landed.y, 0.0, 1e-12);
  EXPECT_NEAR(landed.z, -1.0, 1e-12);
  EXPECT_EQ(own.source, "the model's default");
  EXPECT_EQ(defaultPlacementFor("not json").scale, own.scale);
}
