// Loading transforms.json (Blender, Nerfstudio, instant-ngp) and Middlebury *_par.txt from
// tiny synthetic datasets: intrinsics, compositing, missing images, split, downscale, errors.
#include "dataset/dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "dataset/dataset_image.h"
#include "dataset/middlebury.h"
#include "dataset/scene_box.h"
#include "dataset_test_util.h"
#include "fixtures.h"

using namespace inim;
using namespace dataset_test;
using fixtures::expectInputError;
using nlohmann::json;
namespace fs = std::filesystem;

TEST(Dataset, BlenderVariant) {
  std::string d = blenderDataset("blender", 3, 8, {1.0f, 0.0f, 0.0f, 0.6f});
  Dataset ds = loadDataset(d);  // folder with transforms_train.json only
  EXPECT_EQ(ds.format, "blender");
  ASSERT_EQ(ds.frames.size(), 3u);
  const DatasetFrame& f = ds.frames[1];
  EXPECT_EQ(f.intrinsics.width, 8);
  EXPECT_NEAR(f.intrinsics.fx, 0.5 * 8 / std::tan(0.5 * 0.6911112070083618), 1e-12);
  EXPECT_EQ(f.intrinsics.fy, f.intrinsics.fx);
  EXPECT_EQ(f.intrinsics.cx, 4.0);
  EXPECT_TRUE(f.hadAlpha);
  EXPECT_TRUE(fs::path(f.imagePath).filename() == "r_1.png");
  // Straight red at alpha 0.6 (153/255) over white: premultiplied composite.
  float a = 153.0f / 255.0f;
  EXPECT_NEAR(f.image.at(3, 3, 0), 1.0f, 1e-6);
  EXPECT_NEAR(f.image.at(3, 3, 1), 1.0f - a, 1e-6);
  EXPECT_NEAR(f.image.at(3, 3, 2), 1.0f - a, 1e-6);
  // The pose is stored as written.
  EXPECT_NEAR(glm::length(f.position() - glm::dvec3(ringPoses(3)[1][3])), 0.0, 1e-9);
}

TEST(Dataset, BackgroundChoices) {
  std::string d = blenderDataset("background", 1, 4, {0.2f, 0.4f, 1.0f, 0.0f});
  DatasetOptions o;
  o.background = glm::vec3(0.0f);
  Dataset black = loadDataset(d + "/transforms_train.json", o);
  EXPECT_EQ(black.frames[0].image.at(0, 0, 2), 0.0f);  // fully transparent -> background
  o.background = glm::vec3(0.25f, 0.5f, 0.75f);
  Dataset grey = loadDataset(d, o);
  EXPECT_NEAR(grey.frames[0].image.at(1, 1, 0), 0.25f, 1e-6);
  EXPECT_NEAR(grey.frames[0].image.at(1, 1, 2), 0.75f, 1e-6);
  EXPECT_EQ(grey.background, o.background);
}

TEST(Dataset, NerfstudioVariantWithPerFrameOverrides) {
  std::string d = folder("nerfstudio");
  fs::create_directories(d + "/images");
  json j = {{"camera_model", "OPENCV"}, {"fl_x", 10.0}, {"fl_y", 11.0}, {"cx", 6.5}, {"cy", 4.25},
            {"w", 12}, {"h", 8}, {"k1", -0.05}, {"k2", 0.01}, {"p1", 0.001}, {"p2", -0.002}};
  auto poses = ringPoses(2);
  for (int i = 0; i < 2; ++i) {
    writePng(d + "/images/frame_000" + std::to_string(i + 1) + ".png", 12, 8, {0.5f, 0.5f, 0.5f});
    j["frames"].push_back({{"file_path", "images/frame_000" + std::to_string(i + 1) + ".png"},
                           {"transform_matrix", matrixJson(poses[i])}});
  }
  j["frames"][1]["fl_x"] = 20.0;  // per-frame overrides global
  j["frames"][1]["k1"] = 0.0;
  writeBytes(d + "/transforms.json", j.dump());
  Dataset ds = loadDataset(d);
  EXPECT_EQ(ds.format, "nerfstudio");
  ASSERT_EQ(ds.frames.size(), 2u);
  const Intrinsics& a = ds.frames[0].intrinsics;
  EXPECT_EQ(a.fx, 10.0);
  EXPECT_EQ(a.fy, 11.0);
  EXPECT_EQ(a.cx, 6.5);
  EXPECT_EQ(a.k1, -0.05);
  EXPECT_EQ(a.p2, -0.002);
  EXPECT_EQ(ds.frames[1].intrinsics.fx, 20.0);
  EXPECT_EQ(ds.frames[1].intrinsics.fy, 11.0);
  EXPECT_EQ(ds.frames[1].intrinsics.k1, 0.0);
  EXPECT_FALSE(ds.frames[0].hadAlpha);
  EXPECT_NEAR(ds.frames[0].image.at(0, 0, 0), 128.0f / 255.0f, 1e-6);

  // PINHOLE ignores distortion; other models are rejected.
  j["camera_model"] = "PINHOLE";
  writeBytes(d + "/transforms.json", j.dump());
  EXPECT_EQ(loadDataset(d).frames[0].intrinsics.k1, 0.0);
  j["camera_model"] = "OPENCV_FISHEYE";
  writeBytes(d + "/transforms.json", j.dump());
  InputError e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.key(), "camera_model");
  EXPECT_EQ(e.value(), "OPENCV_FISHEYE");
  j["camera_model"] = "OPENCV";
  j["k3"] = 0.2;
  writeBytes(d + "/transforms.json", j.dump());
  EXPECT_EQ(expectInputError([&] { loadDataset(d); }).key(), "k3");
}

TEST(Dataset, InstantNgpVariantRecordsItsBox) {
  std::string d = folder("ngp");
  json j = {{"fl_x", 5.0}, {"w", 4}, {"h", 4}, {"aabb_scale", 4}, {"scale", 0.5},
            {"offset", {0.5, 1.5, 0.5}}};
  auto poses = ringPoses(2);
  for (int i = 0; i < 2; ++i) {
    writePng(d + "/f" + std::to_string(i) + ".jpg.png", 4, 4, {0.1f, 0.2f, 0.3f});
    j["frames"].push_back({{"file_path", "f" + std::to_string(i) + ".jpg"},  // .jpg absent: try .png
                           {"transform_matrix", matrixJson(poses[i])}});
  }
  writeBytes(d + "/transforms.json", j.dump());
  Dataset ds = loadDataset(d + "/transforms.json");
  EXPECT_EQ(ds.format, "instant-ngp");
  ASSERT_TRUE(ds.ngpBox.has_value());
  // [0.5 -+ 2]^3 in ngp space, minus the offset (world axis order), / scale.
  EXPECT_NEAR(ds.ngpBox->lo.x, -4.0, 1e-12);
  EXPECT_NEAR(ds.ngpBox->lo.y, -6.0, 1e-12);
  EXPECT_NEAR(ds.ngpBox->hi.y, 2.0, 1e-12);
  EXPECT_NEAR(ds.ngpBox->hi.z, 4.0, 1e-12);
  EXPECT_EQ(ds.frames[0].intrinsics.cx, 2.0);  // absent cx: image centre
  // The poses are not rescaled.
  EXPECT_NEAR(glm::length(ds.frames[1].position() - glm::dvec3(poses[1][3])), 0.0, 1e-9);
}

TEST(Dataset, MissingImagesAreSkippedAndCounted) {
  std::string d = blenderDataset("missing", 10, 4, {1, 1, 1, 1});
  for (int i : {2, 5, 9}) fs::remove(d + "/train/r_" + std::to_string(i) + ".png");
  testing::internal::CaptureStderr();
  Dataset ds = loadDataset(d);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(ds.skippedFrames, 3);
  ASSERT_EQ(ds.frames.size(), 7u);
  EXPECT_EQ(ds.frames[2].sourceIndex, 3);
  EXPECT_NE(err.find("skipped 3 of 10 frames whose images are missing"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);  // once
}

TEST(Dataset, TrainTestSplit) {
  std::vector<int> train, test;
  splitTrainTest(17, 8, train, test);
  EXPECT_EQ(test, (std::vector<int>{0, 8, 16}));
  EXPECT_EQ(train.size(), 14u);
  splitTrainTest(5, 0, train, test);
  EXPECT_TRUE(test.empty());
  EXPECT_EQ(train.size(), 5u);

  std::string d = blenderDataset("split", 10, 2, {1, 1, 1});
  DatasetOptions o;
  o.holdoutEvery = 3;
  Dataset ds = loadDataset(d, o);
  EXPECT_EQ(ds.test, (std::vector<int>{0, 3, 6, 9}));
  EXPECT_EQ(ds.train, (std::vector<int>{1, 2, 4, 5, 7, 8}));
}

TEST(Dataset, DownscaleAveragesAndScalesIntrinsics) {
  std::string d = folder("downscale");
  // 8x4 image: left half black, right half white -> at factor 2, a 4x2 image; pixel 1 and 2
  // straddle nothing, so values stay exact; a checker would average to 0.5.
  auto out = OIIO::ImageOutput::create(d + "/a.png");
  OIIO::ImageSpec spec(8, 4, 3, OIIO::TypeDesc::UINT8);
  std::vector<unsigned char> px(8 * 4 * 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) px[(y * 8 + x) * 3 + c] = (x >= 4) ? 255 : ((x + y) % 2 ? 255 : 0);
  out->open(d + "/a.png", spec);
  out->write_image(OIIO::TypeDesc::UINT8, px.data());
  out->close();
  json j = {{"fl_x", 8.0}, {"cx", 4.0}, {"cy", 2.0}, {"w", 8}, {"h", 4}};
  j["frames"].push_back({{"file_path", "a.png"}, {"transform_matrix", matrixJson(ringPoses(1)[0])}});
  writeBytes(d + "/transforms.json", j.dump());
  DatasetOptions o;
  o.downscale = 2;
  Dataset ds = loadDataset(d, o);
  const DatasetFrame& f = ds.frames[0];
  EXPECT_EQ(f.image.width, 4);
  EXPECT_EQ(f.image.height, 2);
  EXPECT_EQ(f.intrinsics.width, 4);
  EXPECT_EQ(f.intrinsics.fx, 4.0);
  EXPECT_EQ(f.intrinsics.fy, 4.0);
  EXPECT_EQ(f.intrinsics.cx, 2.0);
  EXPECT_EQ(f.intrinsics.cy, 1.0);
  EXPECT_NEAR(f.image.at(0, 0, 0), 0.5f, 1e-6);  // checker averages to grey
  EXPECT_NEAR(f.image.at(3, 1, 1), 1.0f, 1e-6);
  // Sizes that are not a multiple go through OIIO's resize: 9x6 at 4 -> 2x2 (rounded).
  Image odd(9, 6, {"R", "G", "B"});
  std::fill(odd.data.begin(), odd.data.end(), 0.25f);
  Image small = downscaleImage(odd, 4);
  EXPECT_EQ(small.width, 2);
  EXPECT_EQ(small.height, 2);
  EXPECT_NEAR(small.at(1, 1, 2), 0.25f, 1e-5);
  // The size check is made at full resolution.
  j["w"] = 4;
  writeBytes(d + "/transforms.json", j.dump());
  EXPECT_NE(expectInputError([&] { loadDataset(d, o); }).key().find("(w, h)"), std::string::npos);
}

TEST(Dataset, BadInputNamesFileKeyAndValue) {
  std::string d = blenderDataset("bad", 2, 4, {1, 1, 1});
  std::string file = d + "/transforms_train.json";
  json good = json::parse(std::ifstream(file));

  // Non-finite pose (a literal too large for a double parses as inf).
  json j = good;
  j["frames"][1]["transform_matrix"][0][3] = "NaN";
  writeBytes(file, j.dump());
  InputError e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.file(), file);
  EXPECT_EQ(e.key(), "frames[1].transform_matrix");
  writeBytes(file, good.dump().replace(good.dump().find("\"transform_matrix\":[[") + 21, 1, "1e999,"));
  e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.file(), file);
  EXPECT_NE(e.expected().find("finite"), std::string::npos) << e.what();

  // Image size disagreeing with w/h.
  j = good;
  j["w"] = 5;
  j["h"] = 4;
  writeBytes(file, j.dump());
  e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.value(), "5x4");
  EXPECT_NE(e.expected().find("4x4"), std::string::npos);

  // Missing intrinsics.
  j = good;
  j.erase("camera_angle_x");
  writeBytes(file, j.dump());
  e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.key(), "frames[0].fl_x");

  // Malformed JSON.
  writeBytes(file, "{\"frames\": [");
  e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.file(), file);

  // Empty dataset: no frame has an image.
  j = good;
  j["frames"][0]["file_path"] = "nowhere/a";
  j["frames"][1]["file_path"] = "nowhere/b";
  writeBytes(file, j.dump());
  e = expectInputError([&] { loadDataset(d); });
  EXPECT_EQ(e.key(), "frames");
  j["frames"] = json::array();
  writeBytes(file, j.dump());
  expectInputError([&] { loadDataset(d); });

  // Bad options and paths.
  writeBytes(file, good.dump());
  DatasetOptions o;
  o.downscale = 0;
  EXPECT_EQ(expectInputError([&] { loadDataset(d, o); }).key(), "downscale");
  expectInputError([&] { loadDataset(d + "/nonexistent"); });
  expectInputError([&] { loadDataset(folder("emptyfolder")); });
}

// A Middlebury file: K [R | t] projects a world point where projectToFrame does (+0.5 px for
// the pixel-centre convention) and frameRay through that pixel passes through the point.
TEST(Dataset, MiddleburyConversion) {
  std::string d = folder("middlebury");
  glm::dmat3 K(0.0);
  K[0][0] = 1520.4; K[1][1] = 1525.9; K[2][0] = 302.32; K[2][1] = 246.87; K[2][2] = 1.0;
  // A rotation from a real temple camera, orthonormalised, and its t.
  glm::dvec3 r0(0.02187598221295043, 0.98329680886213122, -0.18068986436368856);
  glm::dvec3 r1(0.99856708067455469, -0.01266114646423925, 0.05199500709979997);
  r1 = glm::normalize(r1 - glm::dot(r1, glm::normalize(r0)) * glm::normalize(r0));
  r0 = glm::normalize(r0);
  glm::dvec3 r2 = glm::cross(r0, r1);
  glm::dvec3 t(-0.0726637729648, 0.0223360353405, 0.614604845959);
  std::string line = "img0.png";
  for (double v : {K[0][0], K[1][0], K[2][0], K[0][1], K[1][1], K[2][1], K[0][2], K[1][2], K[2][2]})
    line += " " + std::to_string(v);
  char buf[64];
  for (glm::dvec3 r : {r0, r1, r2})
    for (int c = 0; c < 3; ++c) {
      std::snprintf(buf, sizeof buf, " %.17g", r[c]);
      line += buf;
    }
  for (int c = 0; c < 3; ++c) {
    std::snprintf(buf, sizeof buf, " %.17g", t[c]);
    line += buf;
  }
  writeBytes(d + "/test_par.txt", "1\n" + line + "\n");
  writePng(d + "/img0.png", 640, 480, {0, 0, 0});
  Dataset ds = loadDataset(d);
  EXPECT_EQ(ds.format, "middlebury");
  const DatasetFrame& f = ds.frames[0];
  EXPECT_EQ(f.intrinsics.width, 640);
  EXPECT_NEAR(f.intrinsics.cx, 302.32 + 0.5, 1e-9);

  glm::dmat3 R;  // rows r0 r1 r2
  for (int c = 0; c < 3; ++c) { R[c][0] = r0[c]; R[c][1] = r1[c]; R[c][2] = r2[c]; }
  for (glm::dvec3 X : {glm::dvec3(0.0, 0.1, 0.0), glm::dvec3(-0.05, 0.02, 0.03), glm::dvec3(0.02, 0.15, -0.01)}) {
    glm::dvec3 x = K * (R * X + t);
    glm::dvec2 raw(x.x / x.z, x.y / x.z);
    glm::dvec2 p;
    ASSERT_TRUE(projectToFrame(f, X, p));
    EXPECT_NEAR(p.x, raw.x + 0.5, 1e-6);
    EXPECT_NEAR(p.y, raw.y + 0.5, 1e-6);
    glm::dvec3 o, dir;
    frameRay(f, p.x, p.y, o, dir);
    glm::dvec3 toX = X - o;
    EXPECT_NEAR(glm::length(toX - glm::dot(toX, dir) * dir), 0.0, 1e-9);
    EXPECT_GT(glm::dot(toX, dir), 0.0);
  }
  // A malformed line names it.
  writeBytes(d + "/test_par.txt", "1\nimg0.png 1 2 3\n");
  EXPECT_EQ(expectInputError([&] { loadDataset(d); }).key(), "line 2");
}

TEST(SceneBox, RingOfCamerasFindsTheCentre) {
  std::vector<DatasetFrame> frames;
  glm::dvec3 c(0.3, -0.2, 0.5);
  for (int i = 0; i < 12; ++i) {
    double a = 2 * M_PI * i / 12, el = (i % 2 ? 0.3 : 0.6);
    DatasetFrame f;
    f.intrinsics.width = f.intrinsics.height = 100;
    f.intrinsics.fx = f.intrinsics.fy = 100;  // tan(half fov) = 0.5
    glm::dvec3 eye = c + 3.0 * glm::dvec3(std::cos(el) * std::cos(a), std::sin(el), std::cos(el) * std::sin(a));
    f.cameraToWorld = lookAtC2W(eye, c);
    frames.push_back(f);
  }
  SceneBoxEstimate e = estimateSceneBox(frames);
  EXPECT_TRUE(e.axesConverge);
  EXPECT_NEAR(glm::length(e.box.center() - c), 0.0, 1e-9);
  EXPECT_NEAR(e.box.extent().x, 3.0, 1e-9);  // 2 * 3 * 0.5
  EXPECT_NEAR(e.nearPlane, 3.0 - 1.5 * std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(e.farPlane, 3.0 + 1.5 * std::sqrt(3.0), 1e-9);

  // Forward-facing (parallel axes): a finite fallback in front of the cameras.
  for (size_t i = 0; i < frames.size(); ++i)
    frames[i].cameraToWorld = glm::translate(glm::dmat4(1.0), glm::dvec3(0.1 * i, 0.05 * (i % 3), 0));
  e = estimateSceneBox(frames);
  EXPECT_FALSE(e.axesConverge);
  EXPECT_LT(e.box.center().z, 0.0);
  EXPECT_TRUE(std::isfinite(e.farPlane));
}
