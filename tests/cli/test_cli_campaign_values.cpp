// Cases of the bad-input campaign that reached the outputs or blamed the wrong place: gaps no
// display can have (a 1e-300 mm gap made rays parallel to the panel), a viewing distance whose
// toed-in EIA overflowed the pixel counts, a lens without power (NaN focal lengths), NaN rays in
// an .irays input, zero sizes that silently meant "default", a gap or camera distance the optics
// cannot take blamed on the MLA or lens file instead of the option, and a relative RMSE of black
// images. Each: exit status 2, one message naming the setting, nothing written.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/image.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

ScratchDir scratchFolder("test_cli_campaign_values");
std::string path(const std::string& name) { return scratchFolder.path(name); }

void expectBadInput(const std::string& args, std::initializer_list<std::string> needles,
                    std::initializer_list<std::string> outputs) {
  expectBadInputWith([](const std::string& a) { return runInim(a); }, args, needles, outputs);
}

// The prototype with one value changed (its panel and MLA by absolute path).
std::string prototypeWith(const std::string& name, const std::string& key, const std::string& value,
                          const std::string& base = "optics/displays/paper-prototype.json") {
  std::ifstream in(data(base));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto replace = [&](const std::string& k, const std::string& v) {
    const size_t at = text.find("\"" + k + "\":");
    const size_t start = text.find(':', at) + 1, end = text.find_first_of(",\n}", start);
    text.replace(start, end - start, " " + v);
  };
  replace("panel", "\"" + data("optics/panels/sony-xperia-1-ii.json") + "\"");
  replace("mla", "\"" + data("optics/mlas/fresnel-630.json") + "\"");
  replace(key, value);
  const std::string file = path(name);
  writeText(file, text);
  return file;
}

}  // namespace

TEST(CliCampaignValues, GapsNoDisplayCanHaveAreRefusedWhereverGiven) {
  const std::string out = path("rays.txt");
  expectBadInput("rays --gap-mm 1e-300 --out " + out, {"--gap-mm", "1e-300", "0.001"}, {out});
  expectBadInput("rays --gap-mm 1e5 --out " + out, {"--gap-mm"}, {out});
  const std::string tiny = prototypeWith("tiny-gap.json", "generation_gap_mm", "1e-300");
  expectBadInput("display info " + tiny, {"tiny-gap.json", "generation_gap_mm", "1e-300"}, {});
  expectBadInput("rays --display " + tiny + " --out " + out, {"tiny-gap.json", "generation_gap_mm"}, {out});
}

TEST(CliCampaignValues, ViewBlamesTheOptionNotTheOpticsFile) {
  const std::string eia = path("eia.exr"), out = path("view.exr");
  writeImage(Image(3840, 1644, {"R", "G", "B"}), eia);
  const std::string base = "view --eia " + eia + " --width 32 --out " + out;
  // Below the range every gap is refused alike; inside it, the real MLA's own limit names the option.
  expectBadInput(base + " --gap-mm 1e-6", {"--gap-mm", "0.001"}, {out});
  const CliResult r = runInim(base + " --gap-mm 0.5");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("'--gap-mm'"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("fresnel-630.json"), std::string::npos) << r.output;
  const CliResult d = runInim(base + " --distance-mm 1");
  EXPECT_EQ(d.status, 2) << d.output;
  EXPECT_NE(d.output.find("'--distance-mm'"), std::string::npos) << d.output;
  EXPECT_EQ(d.output.find("edmund-85-351-standin.json"), std::string::npos) << d.output;
  expectBadInput("view --eia " + eia + " --out " + out + " --focus-mm 0", {"--focus-mm"}, {out});
  expectBadInput("view --eia " + eia + " --out " + out + " --width 0", {"--width"}, {out});
  expectBadInput("view --eia " + eia + " --out " + out + " --height 0", {"--height"}, {out});
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliCampaignValues, ToedInDistanceThatOverflowsThePanelIsNamed) {
  const std::string d = prototypeWith("near.json", "viewing_distance_mm", "1e-9",
                                      "optics/displays/paper-prototype-toed-in.json");
  const CliResult r = runInim("display info " + d);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("viewing_distance_mm"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(" -"), std::string::npos) << "no negative pixel counts: " << r.output;
}

TEST(CliCampaignValues, LensWithoutPowerIsRefusedNotNan) {
  const std::string lens = path("stop-only.dat");
  writeText(lens, "# a stop and nothing else\n0\t5\t0\t10\n");
  const CliResult r = runInim("lens info " + lens);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("stop-only.dat"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("optical power"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("nan"), std::string::npos) << r.output;
}

TEST(CliCampaignValues, NanRayInAnIraysInputIsRefused) {
  const std::string display = path("small.json"), rays = path("rays.irays"), out = path("from-nan.txt");
  writeText(display, smallDisplayJson(4, 3, 5));
  ASSERT_EQ(runInim("rays --display " + display + " --out " + rays).status, 0);
  std::fstream f(rays, std::ios::in | std::ios::out | std::ios::binary);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  f.seekp(48 + 4 * 2);  // the third ray's origin x (columns of floats after the 48-byte header)
  f.write(reinterpret_cast<const char*>(&nan), sizeof nan);
  f.close();
  expectBadInput("rays --in " + rays + " --out " + out, {"rays.irays", "ray 2", "nan", "finite origin"}, {out});
}

TEST(CliCampaignValues, RelativeRmseOfBlackImagesIsNotNan) {
  const std::string a = path("black-a.png"), b = path("black-b.png");
  writeImage(Image(1, 1, {"R", "G", "B"}), a);
  writeImage(Image(1, 1, {"R", "G", "B"}), b);
  const CliResult r = runInim("compare " + a + " " + b);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("nan"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("RMSE         n/a"), std::string::npos) << r.output;
}
