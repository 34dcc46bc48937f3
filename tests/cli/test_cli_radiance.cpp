// Command-line tests of the radiance-field workflow: inim capture -> train -> eval, a trained
// field driving inim eia / render, and the ray exchange (rays --for-field, query,
// eia --field-colors) reproducing inim eia --field exactly. Bad input: exit status 2, a
// message naming the file and key, and no output left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/image.h"
#include "core/npy.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

ScratchDir scratch("test_cli_radiance");
std::string path(const std::string& name) { return scratch.path(name); }

void expectBadInput(const std::string& args, std::initializer_list<std::string> needles,
                    std::initializer_list<std::string> outputs) {
  expectBadInputWith([](const std::string& a) { return runInim(a); }, args, needles, outputs);
}

std::string smallDisplay() {
  static std::string f = [] {
    std::string p = path("small.json");
    writeText(p, smallDisplayJson(11, 9, 9));
    return p;
  }();
  return f;
}

// A small capture of the paper's scene and a model trained on it (once for the suite).
struct Trained {
  std::string data, model;
  CliResult capture, train;
};
const Trained& trained() {
  static Trained t = [] {
    Trained r;
    r.data = path("capture");
    r.model = path("model.inimrf");
    r.capture = runInim("capture --scene " + data("scenes/paper-fig7.json") + " --out " + r.data +
                        " --views 24 --width 48 --height 36 --spp 32 --target -60,-30,-20,60,30,40 --quiet");
    r.train = runInim("train --data " + r.data + " --out " + r.model +
                      " --background black --iterations 300 --resolutions 32,48 --batch 2048");
    return r;
  }();
  return t;
}

}  // namespace

TEST(CliRadiance, CaptureTrainEvalRoundTrip) {
  const Trained& t = trained();
  ASSERT_EQ(t.capture.status, 0) << t.capture.output;
  ASSERT_TRUE(fs::exists(t.data + "/transforms.json"));
  ASSERT_EQ(t.train.status, 0) << t.train.output;
  EXPECT_NE(t.train.output.find("held out:"), std::string::npos) << t.train.output;
  EXPECT_TRUE(fs::exists(path("model.csv")));  // the training log beside the model
  CliResult e = runInim("eval --model " + t.model + " --data " + t.data + " --background black --out " + path("eval"));
  ASSERT_EQ(e.status, 0) << e.output;
  // Held-out views of a scene the model has seen from nearby, at a CI-sized 300 iterations on
  // 48 x 36 px photos: well above the 12.8 dB that a 2-spp (noisy) capture gave (the field's
  // own quality targets are tests/radiance and the Lego benchmark).
  const size_t at = e.output.find("PSNR ", e.output.find("mean over"));
  ASSERT_NE(at, std::string::npos) << e.output;
  EXPECT_GT(std::stod(e.output.substr(at + 5)), 16.0) << e.output;
  EXPECT_TRUE(fs::exists(path("eval/metrics.json")));
}

// The exchange reproduces inim's own field exactly: the same rays, the same colours.
TEST(CliRadiance, RayExchangeReproducesTheFieldsOwnEia) {
  const Trained& t = trained();
  ASSERT_EQ(t.train.status, 0) << t.train.output;
  const std::string common = " --display " + smallDisplay() + " --translate-mm 0,0,5";
  CliResult a = runInim("eia" + common + " --field " + t.model + " --exposure 1 --aovs --quiet --out " + path("direct.exr"));
  ASSERT_EQ(a.status, 0) << a.output;
  CliResult r = runInim("rays --for-field" + common + " --out " + path("rays.npy"));
  ASSERT_EQ(r.status, 0) << r.output;
  NpyArray rays = readNpy(path("rays.npy"));
  EXPECT_EQ(rays.cols, 8);
  EXPECT_EQ(rays.rows, 11 * 9 * 9 * 9);
  CliResult q = runInim("query --field " + t.model + " --rays " + path("rays.npy") + " --out " + path("colors.npy"));
  ASSERT_EQ(q.status, 0) << q.output;
  CliResult b = runInim("eia" + common + " --field-colors " + path("colors.npy") +
                        " --field-colors-encoding linear --exposure 1 --aovs --quiet --out " + path("exchanged.exr"));
  ASSERT_EQ(b.status, 0) << b.output;
  Image x = readImage(path("direct.exr")), y = readImage(path("exchanged.exr"));
  ASSERT_EQ(x.data.size(), y.data.size());
  double lit = 0;
  for (size_t i = 0; i < x.data.size(); ++i) {
    EXPECT_NEAR(x.data[i], y.data[i], 1e-5f) << "value " << i;
    lit += x.data[i];
  }
  EXPECT_GT(lit, 0.0);  // the field is seen
  // Same rows, wrong spp: a clear error and no EIA.
  expectBadInput("eia" + common + " --field-colors " + path("colors.npy") + " --spp 2 --out " + path("bad.exr"),
                 {"colors.npy", "shape"}, {path("bad.exr")});
}

// A novel view of the trained field (straight on, 300 mm: no capture camera stood there)
// against the same view of the analytic scene it was trained on: the centre of the image is
// opaque, at the scene's depth and of the scene's colour.
TEST(CliRadiance, NovelViewMatchesTheAnalyticScene) {
  const Trained& t = trained();
  ASSERT_EQ(t.train.status, 0) << t.train.output;
  const std::string camera = " --eye 0,0,300 --look-at 0,0,0 --width 64 --height 48 ";
  CliResult f = runInim("render --field " + t.model + camera + "--spp 1 --out " + path("novel.exr"));
  ASSERT_EQ(f.status, 0) << f.output;
  CliResult s = runInim("render --scene " + data("scenes/paper-fig7.json") + camera + "--spp 64 --out " +
                        path("truth.exr"));
  ASSERT_EQ(s.status, 0) << s.output;
  const Image a = readImage(path("novel.exr")), b = readImage(path("truth.exr"));
  ASSERT_EQ(a.channels, b.channels);  // R G B A Z
  // Means over the central 8 x 8 pixels.
  auto centre = [](const Image& img, int c) {
    double sum = 0.0;
    for (int y = 20; y < 28; ++y)
      for (int x = 28; x < 36; ++x) sum += img.at(x, y, c);
    return sum / 64.0;
  };
  EXPECT_GT(centre(a, 3), 0.9);                                 // opaque, as the scene is
  EXPECT_NEAR(centre(a, 4), centre(b, 4), 0.1 * centre(b, 4));  // depth within 10 %
  // The CI-sized model (300 iterations) is soft here, where the yellow filter's edge meets the
  // green can: measured R, G, B 0.658, 0.584, 0.305 against 0.803, 0.647, 0.364 converged (the
  // model 0.70 in R after 800 iterations). 0.15 bounds that softness, not noise (64 samples).
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre(a, c), centre(b, c), 0.15) << "channel " << c;
}

TEST(CliRadiance, BadModelsAndDatasetsAreInputErrors) {
  const std::string junk = path("junk.inimrf");
  writeText(junk, "this is not a model");
  expectBadInput("eia --field " + junk + " --out " + path("e.exr"), {"junk.inimrf", "header"}, {path("e.exr")});
  // An empty dataset.
  fs::create_directories(path("empty"));
  writeText(path("empty/transforms.json"), R"({"camera_angle_x": 0.7, "frames": []})");
  expectBadInput("train --data " + path("empty") + " --out " + path("m.inimrf"), {"transforms.json"}, {path("m.inimrf")});
  // A non-finite pose.
  fs::create_directories(path("nan"));
  writeText(path("nan/transforms.json"),
            R"({"camera_angle_x": 0.7, "frames": [{"file_path": "a.png", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,1e999],[0,0,0,1]]}]})");
  CliResult r = runInim("train --data " + path("nan") + " --out " + path("m.inimrf"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(fs::exists(path("m.inimrf")));
  expectBadInput("train --data " + path("nowhere") + " --out " + path("m.inimrf"), {"nowhere"}, {path("m.inimrf")});
  expectBadInput("train --data " + path("empty") + " --out " + path("m.bin"), {"--out", "m.bin"}, {path("m.bin")});
}
