// transforms.json as the tools write it: instant-ngp's colmap2nerf.py (sizes as floats,
// "sharpness" per frame, camera_angle and focal lengths both), Nerfstudio's colmap_to_json
// ("colmap_im_id", "applied_transform", "ply_file_path"); a misspelt key is refused.
#include <gtest/gtest.h>

#include <string>

#include "dataset/transforms_json.h"
#include "dataset_test_util.h"
#include "fixtures.h"

using namespace inim;
using namespace dataset_test;
using fixtures::expectInputError;
using nlohmann::json;

namespace {

json identityPose() { return matrixJson(glm::dmat4(1.0)); }

// The key set of instant-ngp's scripts/colmap2nerf.py for one camera (data/nerf/fox writes
// "w": 1080.0): every camera key at the top, frames with file_path, sharpness, transform_matrix.
json instantNgpFile() {
  json j = {{"camera_angle_x", 1.1}, {"camera_angle_y", 1.5}, {"fl_x", 1100.0}, {"fl_y", 1101.0},
            {"k1", 0.01}, {"k2", -0.002}, {"k3", 0}, {"k4", 0}, {"p1", 0.0001}, {"p2", -0.0001},
            {"is_fisheye", false}, {"cx", 540.0}, {"cy", 960.0}, {"w", 1080.0}, {"h", 1920.0},
            {"aabb_scale", 4}};
  j["frames"].push_back({{"file_path", "./images/0001.jpg"}, {"sharpness", 31.5}, {"transform_matrix", identityPose()}});
  return j;
}

// The key set of Nerfstudio's process_data colmap_to_json.
json nerfstudioFile() {
  json j = {{"w", 1080}, {"h", 1920}, {"fl_x", 1100.0}, {"fl_y", 1101.0}, {"cx", 540.0}, {"cy", 960.0},
            {"k1", 0.01}, {"k2", -0.002}, {"p1", 0.0001}, {"p2", -0.0001}, {"camera_model", "OPENCV"}};
  j["frames"].push_back({{"file_path", "images/frame_00001.jpg"}, {"transform_matrix", identityPose()},
                         {"colmap_im_id", 1}, {"mask_path", "masks/mask.png"}, {"depth_file_path", "depths/1.png"}});
  j["applied_transform"] = {{1, 0, 0, 0}, {0, 0, 1, 0}, {0, -1, 0, 0}};
  j["ply_file_path"] = "sparse_pc.ply";
  return j;
}

std::string write(const std::string& name, const json& j) {
  return fixtures::scratchFile(name, j.dump(2));
}

}  // namespace

TEST(TransformsJson, InstantNgpSizesWrittenAsFloatsAreRead) {
  DatasetManifest m = readTransformsJson(write("ngp.json", instantNgpFile()));
  EXPECT_EQ(m.format, "instant-ngp");
  ASSERT_EQ(m.frames.size(), 1u);
  EXPECT_EQ(m.frames[0].intrinsics.width, 1080);
  EXPECT_EQ(m.frames[0].intrinsics.height, 1920);
  EXPECT_EQ(m.frames[0].intrinsics.fx, 1100.0);
  EXPECT_EQ(m.frames[0].intrinsics.k1, 0.01);
}

TEST(TransformsJson, NerfstudioExtrasAreAccepted) {
  DatasetManifest m = readTransformsJson(write("ns.json", nerfstudioFile()));
  EXPECT_EQ(m.format, "nerfstudio");
  ASSERT_EQ(m.frames.size(), 1u);
  EXPECT_EQ(m.frames[0].intrinsics.width, 1080);
  EXPECT_EQ(m.frames[0].intrinsics.cy, 960.0);
}

TEST(TransformsJson, FractionalSizeRefusedNamingFileKeyAndValue) {
  json j = instantNgpFile();
  j["w"] = 1080.5;
  const std::string file = write("ngp-frac.json", j);
  InputError e = expectInputError([&] { readTransformsJson(file); });
  EXPECT_EQ(e.file(), file);
  EXPECT_EQ(e.key(), "w");
  EXPECT_EQ(e.value(), "1080.5");
  j["w"] = 4294967304.0;  // never wrapped to 8
  const std::string wrap = write("ngp-wrap.json", j);
  EXPECT_EQ(expectInputError([&] { readTransformsJson(wrap); }).value(), "4294967304.0");
}

TEST(TransformsJson, MisspeltKeyRefused) {
  json j = nerfstudioFile();
  j["fl_z"] = 1100.0;
  const std::string top = write("ns-flz.json", j);
  InputError e = expectInputError([&] { readTransformsJson(top); });
  EXPECT_EQ(e.file(), top);
  EXPECT_EQ(e.key(), "fl_z");
  j.erase("fl_z");
  j["frames"][0]["fl_z"] = 1100.0;
  const std::string frame = write("ns-flz-frame.json", j);
  EXPECT_EQ(expectInputError([&] { readTransformsJson(frame); }).key(), "frames[0].fl_z");
}

TEST(TransformsJson, FisheyePerFrameRefused) {
  json j = instantNgpFile();
  j["frames"][0]["is_fisheye"] = true;  // colmap2nerf.py writes camera keys per frame for several cameras
  const std::string file = write("ngp-fisheye.json", j);
  EXPECT_EQ(expectInputError([&] { readTransformsJson(file); }).key(), "frames[0].is_fisheye");
}
