// The render command: bad input gives one clear message, exit status 2, and no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/run_cli.h"

namespace fs = std::filesystem;

namespace {
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("inim_cli_render_" + std::to_string(::getpid()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
  bool empty() const {
    for (auto& e : fs::directory_iterator(path))
      if (e.path().extension() == ".exr" || e.path().extension() == ".png") return false;
    return true;
  }
};

// Expects exit 2, a message containing every `needles`, and no image written.
void expectRejected(const TempDir& dir, const std::string& sceneText,
                    std::initializer_list<std::string> needles) {
  std::string scene = dir.write("scene.json", sceneText);
  CliResult r = runInim("render --scene " + scene + " --out " + (dir.path / "out.exr").string() +
                        " --width 8 --height 8 --spp 1");
  EXPECT_EQ(r.status, 2) << r.output;
  for (const auto& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << "missing '" << n << "' in: " << r.output;
  EXPECT_TRUE(dir.empty()) << "partial output left behind";
}

const char* kGood = R"({
  "materials": {"white": {"type": "diffuse", "reflectance": 0.5}},
  "objects": [{"type": "sphere", "radius_mm": 5, "material": "white"}],
  "lights": [{"type": "point", "position_mm": [0, 0, 50], "scale": 1000}]
})";
}  // namespace

TEST(CliRender, GoodSceneWritesExrAndPng) {
  TempDir dir;
  std::string scene = dir.write("scene.json", kGood);
  CliResult r = runInim("render --scene " + scene + " --out " + (dir.path / "img.exr").string() +
                        " --width 16 --height 12 --spp 2 --eye 0,0,40");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir.path / "img.exr"));
  EXPECT_TRUE(fs::exists(dir.path / "img.png"));
}

TEST(CliRender, MalformedJson) {
  TempDir dir;
  expectRejected(dir, "{\"objects\": [", {"scene.json", "malformed JSON"});
}

TEST(CliRender, MisspeltKey) {
  TempDir dir;
  std::string s = kGood;
  s.replace(s.find("radius_mm"), 9, "raduis_mm");
  expectRejected(dir, s, {"scene.json", "raduis_mm"});
}

TEST(CliRender, NegativeSize) {
  TempDir dir;
  std::string s = kGood;
  s.replace(s.find("\"radius_mm\": 5"), 14, "\"radius_mm\": -5");
  expectRejected(dir, s, {"scene.json", "radius_mm", "-5"});
}

TEST(CliRender, UnknownMaterial) {
  TempDir dir;
  std::string s = kGood;
  s.replace(s.find("\"material\": \"white\""), 19, "\"material\": \"whte\"");
  expectRejected(dir, s, {"scene.json", "whte"});
}

TEST(CliRender, MissingSceneFile) {
  TempDir dir;
  CliResult r = runInim("render --scene " + (dir.path / "nope.json").string() + " --out " +
                        (dir.path / "o.exr").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("nope.json"), std::string::npos) << r.output;
  EXPECT_TRUE(dir.empty());
}

TEST(CliRender, BadCommandLineValues) {
  TempDir dir;
  std::string scene = dir.write("scene.json", kGood);
  std::string out = " --out " + (dir.path / "o.exr").string();
  EXPECT_EQ(runInim("render --scene " + scene + out + " --width 0").status, 2);
  EXPECT_EQ(runInim("render --scene " + scene + out + " --spp -1").status, 2);
  EXPECT_EQ(runInim("render --scene " + scene + out + " --eye 1,2").status, 2);
  EXPECT_EQ(runInim("render --scene " + scene + " --out " + (dir.path / "o.png").string()).status, 2);
  EXPECT_TRUE(dir.empty());
}

TEST(Cli, VersionAndHelp) {
  CliResult v = runInim("--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_NE(v.output.find("inim "), std::string::npos);
  for (const char* sub : {"render", "bench", "display", "rays", "eia"}) {
    CliResult h = runInim(std::string(sub) + " --help");
    EXPECT_EQ(h.status, 0) << sub;
    EXPECT_NE(h.output.find("--"), std::string::npos) << sub;
  }
}
