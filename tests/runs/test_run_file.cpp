// The run file (runs/run_file.h): a strict reader whose errors name the file and key.
#include "runs/run_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "fixtures.h"

using namespace inim;
using fixtures::expectInputError;
using fixtures::scratchPath;

TEST(RunFile, SingularPlacementNamesTheFileAndKey) {
  std::string run = scratchPath("singular-run.json");
  {
    std::FILE* fp = std::fopen(run.c_str(), "w");
    std::fputs(R"({"placement": {"scale": [1, 1, 0], "translate_mm": [0, 0, 5]}})", fp);
    std::fclose(fp);
  }
  InputError e2 = expectInputError([&] { (void)loadRunFile(run); });
  EXPECT_EQ(e2.file(), run);
  EXPECT_EQ(e2.key(), "placement.scale");
}

TEST(RunFile, ReadsPlacementAndSettings) {
  std::string run = scratchPath("run.json");
  {
    std::FILE* fp = std::fopen(run.c_str(), "w");
    std::fputs(R"({"_comment": "x", "placement": {"field_units_per_mm": 0.0075, "rotate_deg": [0, 90, 0],
                  "translate_mm": [1, 2, 3]}, "vcp_mm": 25, "spp": 3, "exposure": "auto",
                  "gamut": "desaturate", "layout": "toed-in", "viewing_distance_mm": 400,
                  "triad_wavelengths": [656, 566, 471], "seed": 9, "scene": "s.json",
                  "calibration": "calibration/panel.cube"})",
               fp);
    std::fclose(fp);
  }
  RunFile r = loadRunFile(run);
  ASSERT_TRUE(r.placement);
  EXPECT_NEAR(r.placement->scale.x, 1.0 / 0.0075, 1e-9);
  EXPECT_EQ(r.placement->translateMm, Vec3d(1, 2, 3));
  EXPECT_EQ(*r.vcpMm, 25.0);
  EXPECT_EQ(*r.spp, 3);
  EXPECT_EQ(*r.exposure, "auto");
  EXPECT_EQ(*r.gamut, "desaturate");
  EXPECT_EQ(*r.layout, "toed-in");
  EXPECT_EQ(*r.seed, 9u);
  EXPECT_EQ(*r.triadWavelengths, "656,566,471");
  EXPECT_EQ(std::filesystem::path(*r.scene).parent_path(), std::filesystem::path(run).parent_path());
  EXPECT_EQ(std::filesystem::path(*r.calibration), std::filesystem::path(run).parent_path() / "calibration/panel.cube");

  std::FILE* fp = std::fopen(run.c_str(), "w");
  std::fputs(R"({"vcp": 25})", fp);
  std::fclose(fp);
  InputError e = expectInputError([&] { (void)loadRunFile(run); });
  EXPECT_EQ(e.key(), "vcp");
}

