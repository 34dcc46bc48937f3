// Gaussian-splat scenes through the CLI: `inim render --field X.ply` renders the shipped guitar
// (placed in the display frame on load), and a broken splat file is one message naming the
// file and the property, exit status 2 and no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/run_cli.h"
#include "core/image.h"

namespace fs = std::filesystem;

namespace {

fs::path scratchDir() {
  const fs::path p = fs::temp_directory_path() / ("inim_cli_splats_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

int channel(const inim::Image& im, const std::string& name) {
  for (int c = 0; c < im.numChannels(); ++c)
    if (im.channels[size_t(c)] == name) return c;
  return -1;
}

}  // namespace

// The guitar fills the middle of the default view (camera 350 mm in front of the panel): the
// centre column meets splats about 350 mm away (the scene straddles the MLA plane, its depth
// within the panel height's scale), the corners see nothing.
TEST(CliSplats, RenderTheShippedGuitar) {
  const fs::path dir = scratchDir();
  const std::string out = (dir / "guitar.exr").string();
  const CliResult r = runInim("render --field " + std::string(INIM_SOURCE_DATA_DIR) +
                              "/scenes/splats/guitar.compressed.ply --width 160 --height 90 --spp 1 --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "guitar.png"));
  const inim::Image im = inim::readImage(out, false);
  const int a = channel(im, "A"), z = channel(im, "Z");
  ASSERT_GE(a, 0);
  ASSERT_GE(z, 0);
  float maxAlpha = 0.0f, depthAtMax = 0.0f;
  for (int y = 0; y < im.height; ++y)
    for (int x = im.width / 2 - 8; x < im.width / 2 + 8; ++x)
      if (im.at(x, y, a) > maxAlpha) maxAlpha = im.at(x, y, a), depthAtMax = im.at(x, y, z);
  EXPECT_GT(maxAlpha, 0.9f);
  EXPECT_NEAR(depthAtMax, 350.0f, 65.0f);
  EXPECT_EQ(im.at(0, 0, a), 0.0f);
  EXPECT_EQ(im.at(im.width - 1, im.height - 1, a), 0.0f);
  fs::remove_all(dir);
}

TEST(CliSplats, BrokenSplatFileIsOneMessageAndNoOutput) {
  const fs::path dir = scratchDir();
  const std::string bad = (dir / "bad.ply").string();
  std::ofstream(bad, std::ios::binary) << "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                                          "property float x\nproperty float y\nproperty float z\nend_header\n"
                                       << std::string(12, '\0');
  const CliResult r = runInim("render --field " + bad + " --width 8 --height 8 --spp 1 --out " + (dir / "o.exr").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.ply"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vertex.f_dc_0"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o.exr"));
  EXPECT_FALSE(fs::exists(dir / "o.png"));
  fs::remove_all(dir);
}
