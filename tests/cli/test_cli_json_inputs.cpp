// Every JSON reader through the command line: a file nested 100,000 levels deep, a number
// beyond a double, integers beyond int and a comment each give one message naming the file,
// exit status 2 and no output, instead of a crash (exit 139), a raw library message (exit 1)
// or a silently wrapped value. Runs the built binary (INIM_BINARY; the environment variable
// INIM_TEST_BINARY overrides it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/json_config.h"
#include "scratch_dir.h"

using namespace inim;

namespace {

ScratchDir scratchFolder("test_cli_json");
std::string path(const std::string& name) { return scratchFolder.path(name); }

CliResult run(const std::string& args) {
  const char* b = std::getenv("INIM_TEST_BINARY");
  return runInimBinary(b && *b ? b : INIM_BINARY, args);
}

void expectBadInput(const std::string& args, std::initializer_list<std::string> needles,
                    std::initializer_list<std::string> outputs = {}) {
  expectBadInputWith(run, args, needles, outputs);
}

// `file` (a file of the source tree) with the first `from` replaced by `to`, written to `name`.
std::string edited(const std::string& file, const std::string& name, const std::string& from, const std::string& to) {
  std::string text = fixtures::readBytes(data(file));
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from << " not in " << file;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const std::string f = path(name);
  writeText(f, text);
  return f;
}

const std::string kScene = "scenes/test/point-sphere.json";

// The commands that read each kind of JSON file, `file` standing for it; their outputs.
struct Reader {
  std::string kind, args;
};
std::vector<Reader> readers(const std::string& file) {
  const std::string scene = data(kScene), out = path("out.exr");
  const std::string dataset = path("dataset");
  std::filesystem::create_directories(dataset);
  std::filesystem::copy_file(file, dataset + "/transforms.json", std::filesystem::copy_options::overwrite_existing);
  return {{"display", "display info " + file},
          {"scene", "render --scene " + file + " --out " + out + " --width 8 --height 8 --spp 1"},
          {"lens", "lens info " + file},
          {"camera", "reference --camera " + file + " --out " + out + " --width 8 --spp 1"},
          {"run", "eia --display " + path("small.json") + " --scene " + scene + " --run " + file + " --out " + out},
          {"transforms.json", "train --data " + dataset + " --out " + path("model.inimrf")}};
}

}  // namespace

TEST(CliJsonInputs, DeepNestingRefusedByEveryReader) {
  writeText(path("small.json"), smallDisplayJson(9, 7, 9));
  const std::string deep = path("deep.json");
  writeText(deep, std::string(100000, '[') + std::string(100000, ']'));
  for (const Reader& r : readers(deep)) {
    SCOPED_TRACE(r.kind);
    const std::string shown = r.kind == "transforms.json" ? path("dataset") + "/transforms.json" : deep;
    expectBadInput(r.args, {shown, "nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels"},
                   {path("out.exr"), path("model.inimrf")});
  }
}

TEST(CliJsonInputs, NumberBeyondADoubleNamesFileAndLine) {
  writeText(path("small.json"), smallDisplayJson(9, 7, 9));
  const std::string out = path("out.exr");
  const std::string display = edited("optics/displays/paper-prototype.json", "display-1e400.json",
                                     "\"generation_gap_mm\": 3.3", "\"generation_gap_mm\": 1e400");
  expectBadInput("display info " + display, {display, "1e400", "line 6, column 24"});
  const std::string scene = edited(kScene, "scene-1e400.json", "\"radius_mm\": 0.25", "\"radius_mm\": 1e400");
  expectBadInput("render --scene " + scene + " --out " + out + " --width 8 --height 8 --spp 1", {scene, "1e400", "line"},
                 {out});
  const std::string lens = edited("optics/lenses/edmund-85-351-standin.json", "lens-1e400.json", "\"scale\": 0.238293",
                                  "\"scale\": 1e400");
  expectBadInput("lens info " + lens, {lens, "1e400", "line"});
  const std::string camera = edited("optics/cameras/alvium-1800-u-500c.json", "camera-1e400.json",
                                    "\"distance_mm\": 350.0", "\"distance_mm\": 1e400");
  expectBadInput("reference --camera " + camera + " --out " + out + " --width 8 --spp 1", {camera, "1e400", "line"},
                 {out});
  const std::string runFile = path("run-1e400.json");
  writeText(runFile, "{\n  \"vcp_mm\": 1e400\n}\n");
  expectBadInput("eia --display " + path("small.json") + " --scene " + data(kScene) + " --run " + runFile +
                     " --out " + out,
                 {runFile, "1e400", "line 2, column 13"}, {out});
}

TEST(CliJsonInputs, IntegersBeyondIntAreRefusedNotWrapped) {
  writeText(path("small.json"), smallDisplayJson(9, 7, 9));
  const std::string out = path("out.exr");
  // 2^32 + 8 lenslet columns used to become 8.
  const std::string display = edited("optics/displays/paper-prototype.json", "display-wrap.json",
                                     "\"ei_count\": [153, 65]", "\"ei_count\": [4294967304, 65]");
  expectBadInput("display info " + display, {display, "ei_count", "4294967304"});
  // max_depth 2^32 + 8 used to pass the [0, 1000] check as 8.
  const std::string scene = edited(kScene, "scene-wrap.json", "\"units\": \"mm\",",
                                   "\"units\": \"mm\", \"integrator\": {\"type\": \"path\", \"max_depth\": 4294967304},");
  expectBadInput("render --scene " + scene + " --out " + out + " --width 8 --height 8 --spp 1",
                 {scene, "integrator.max_depth", "4294967304", "[0, 1000]"}, {out});
  // spp 2^32 + 1 used to become 1; 1e12 is named as the number it is.
  for (const std::string& spp : {std::string("4294967297"), std::string("1e12")}) {
    const std::string runFile = path("run-spp.json");
    writeText(runFile, "{\"spp\": " + spp + "}");
    expectBadInput("eia --display " + path("small.json") + " --scene " + data(kScene) + " --run " + runFile +
                       " --out " + out,
                   {runFile, "spp", spp == "1e12" ? "1000000000000" : spp}, {out});
  }
}

TEST(CliJsonInputs, CommentInADisplayFileRefused) {
  const std::string display = edited("optics/displays/paper-prototype.json", "display-comment.json", "{\n",
                                     "{\n  // the paper's prototype\n");
  expectBadInput("display info " + display, {display, "comment (line 2, column 3)", "_comment"});
}
