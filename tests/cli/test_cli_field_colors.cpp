// `inim eia --field-colors` with tables as external renderers write them: without a depth
// column the EIA is filled with no false "empty EIA" warning, no made-up scene extent and an
// automatic exposure taken from the covered rays; A = 0 rows leave their pixels black.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/image.h"
#include "core/npy.h"
#include "scratch_dir.h"

using namespace inim;

namespace {

ScratchDir scratch("test_cli_field_colors");
std::string path(const std::string& name) { return scratch.path(name); }

std::string smallDisplay() {
  static std::string f = [] {
    std::string p = path("small.json");
    writeText(p, smallDisplayJson(7, 5, 5));
    return p;
  }();
  return f;
}

}  // namespace

TEST(CliFieldColors, TableWithoutDepthFillsTheEiaWithoutFalseWarnings) {
  const std::string common = " --display " + smallDisplay() + " --spp 1";
  CliResult r = runInim("rays --for-field" + common + " --out " + path("rays.npy"));
  ASSERT_EQ(r.status, 0) << r.output;
  NpyArray rays = readNpy(path("rays.npy"));
  ASSERT_EQ(rays.rows, 7 * 5 * 5 * 5);
  // R G B A: every other display ray uncovered (A = 0) but with a colour that must not show.
  NpyArray c;
  c.rows = rays.rows, c.cols = 4;
  for (int64_t i = 0; i < c.rows; ++i)
    for (float v : {0.2f, 0.4f, 0.1f, i % 2 ? 0.0f : 1.0f}) c.data.push_back(v);
  writeNpy(path("rgba.npy"), c);
  CliResult e = runInim("eia" + common + " --field-colors " + path("rgba.npy") +
                        " --field-colors-encoding linear --exposure auto --aovs --out " + path("eia.exr"));
  ASSERT_EQ(e.status, 0) << e.output;
  EXPECT_EQ(e.output.find("no query ray hit"), std::string::npos) << e.output;
  EXPECT_EQ(e.output.find("1e+06"), std::string::npos) << e.output;
  EXPECT_NE(e.output.find("real / virtual unknown"), std::string::npos) << e.output;
  EXPECT_EQ(e.output.find("exposure:    1\n"), std::string::npos) << e.output;  // auto, from the covered rays
  Image img = readImage(path("eia.exr"));
  const int a = img.channelIndex("A");
  ASSERT_GE(a, 0);
  int covered = 0, dark = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float m = std::max({img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)});
      if (img.at(x, y, a) > 0.0f) {
        ++covered;
        EXPECT_NEAR(m, 1.0f, 1e-4f);  // auto exposure maps the covered colour to full drive
      } else if (m == 0.0f) {
        ++dark;
      }
    }
  EXPECT_EQ(covered, (7 * 5 * 5 * 5 + 1) / 2);
  EXPECT_EQ(covered + dark, img.width * img.height);  // uncovered and border pixels stay black
}
