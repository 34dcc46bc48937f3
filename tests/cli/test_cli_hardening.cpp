// The second hardening campaign as a regression suite: one case per class of hostile input per
// format, generated from one table. Each ends with exit status 2, a message naming the file or
// flag, the key and the value, and nothing written. The classes: huge finite numbers that used
// to reach the ray tracer, inputs that are not regular files (read until memory ran out, or a
// raw library error), duplicate JSON keys, non-finite or non-unit rays, wrapped integers and
// mirrored placements, unknown commands and hosts, and outputs through symbolic links.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/npy.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

ScratchDir scratchFolder("test_cli_hardening");
std::string path(const std::string& name) { return scratchFolder.path(name); }

std::string readText(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `base` (a file under the source tree) with the value of `"key":` replaced by `value` up to the
// next comma, line end or brace (for an array: its first element, "[100000").
std::string copyWith(const std::string& name, const std::string& base, const std::string& key, const std::string& value) {
  std::string text = readText(data(base));
  const size_t at = text.find("\"" + key + "\":");
  EXPECT_NE(at, std::string::npos) << key;
  const size_t start = text.find(':', at) + 1, end = text.find_first_of(",\n}", start);
  text.replace(start, end - start, " " + value);
  writeText(path(name), text);
  return path(name);
}

// The prototype display on a panel with `key` set to `value`.
std::string displayWithPanel(const std::string& name, const std::string& key, const std::string& value) {
  const std::string panel = copyWith("panel-" + name, "optics/panels/sony-xperia-1-ii.json", key, value);
  std::string d = readText(data("optics/displays/paper-prototype.json"));
  d.replace(d.find("\"sony-xperia-1-ii\""), std::strlen("\"sony-xperia-1-ii\""), "\"" + panel + "\"");
  d.replace(d.find("\"fresnel-630\""), std::strlen("\"fresnel-630\""), "\"" + data("optics/mlas/fresnel-630.json") + "\"");
  writeText(path(name), d);
  return path(name);
}

std::string queryRays(const std::string& name, float ox, float dz) {
  NpyArray a;
  a.rows = 2, a.cols = 8;
  a.data = {0, 0, 100, 0, 0, -1, 0, 1000, ox, 0, 100, 0, 0, dz, 0, 1000};
  writeNpy(path(name), a);
  return path(name);
}

std::string splatFile(const std::string& name, float x) {
  std::string bytes(32, '\0');
  const float f[6] = {x, 0, 0, 1, 1, 1};
  std::memcpy(bytes.data(), f, sizeof f);
  bytes[24] = bytes[25] = bytes[26] = bytes[27] = char(200);
  bytes[28] = char(255), bytes[29] = bytes[30] = bytes[31] = char(128);
  writeText(path(name), bytes);
  return path(name);
}

std::string linkTo(const std::string& name, const std::string& target) {
  fs::remove(path(name));
  fs::create_symlink(target, path(name));
  return path(name);
}

struct Case {
  const char* name;
  std::function<std::string()> args;  // the command line, after its files are made
  std::vector<std::string> needles;   // what the message must name
};

}  // namespace

TEST(CliHardening, EveryClassOfHostileInputEndsInExitTwoWithItsName) {
  const std::string out = path("out.exr"), rays = path("out.irays");
  const std::string scene = data("scenes/paper-fig7.json");
  const std::vector<Case> cases = {
      // Huge finite numbers that reached Embree.
      {"pitch 2^63", [&] { return "rays --display " + displayWithPanel("d1.json", "pixel_pitch_mm", "9.223372036854775808e18") + " --out " + rays; },
       {"pixel_pitch_mm", "9.22337e+18", "[0.0001, 10]"}},
      {"run translate 2^63", [&] {
         writeText(path("r1.json"), R"({"placement": {"translate_mm": [0, 0, 9.223372036854775808e18]}})");
         return "eia --run " + path("r1.json") + " --out " + out; }, {"r1.json", "placement.translate_mm"}},
      {"flag translate 2^63", [&] { return "eia --translate-mm 0,0,9223372036854775808 --out " + out; }, {"--translate-mm", "9223372036854775808"}},
      {"vcp 2^63", [&] { writeText(path("r2.json"), R"({"vcp_mm": 9.223372036854775808e18})");
         return "eia --run " + path("r2.json") + " --out " + out; }, {"r2.json", "vcp_mm"}},
      {"splat 3e38", [&] { return "render --scene " + splatFile("s.splat", 3e38f) + " --width 8 --height 8 --out " + out; },
       {"s.splat", "splat.x", "1e7"}},
      {"npy origin 1e30", [&] { return "query --field " + scene + " --rays " + queryRays("q1.npy", 1e30f, -1) + " --out " + path("c.npy"); },
       {"q1.npy", "row 1", "1e7"}},
      {"npy non-unit", [&] { return "query --field " + scene + " --rays " + queryRays("q2.npy", 0, -0.5f) + " --out " + path("c.npy"); },
       {"q2.npy", "row 1", "unit direction"}},
      // Inputs that are not regular files.
      {"device as display", [&] { return "rays --display " + linkTo("zero.json", "/dev/zero") + " --out " + rays; }, {"zero.json", "a regular file"}},
      {"device as scene", [&] { return "eia --scene " + linkTo("zero2.json", "/dev/urandom") + " --out " + out; }, {"zero2.json", "a regular file"}},
      {"device as lens", [&] { return "lens info " + linkTo("zero.dat", "/dev/zero"); }, {"zero.dat", "a regular file"}},
      {"device as ray text", [&] { return "rays --in " + linkTo("zero.txt", "/dev/zero") + " --out " + rays; }, {"zero.txt", "a regular file"}},
      {"directory as display", [&] { fs::create_directories(path("dir.json")); return "rays --display " + path("dir.json") + " --out " + rays; },
       {"dir.json", "a directory"}},
      {"link loop as scene", [&] { return "eia --scene " + linkTo("loop.json", path("loop.json")) + " --out " + out; },
       {"loop.json", "a loop of symbolic links"}},
      // Duplicate keys, long keys.
      {"duplicate key in a run file", [&] { writeText(path("r3.json"), "{\n\"spp\": 1,\n\"spp\": 2\n}\n");
         return "eia --run " + path("r3.json") + " --out " + out; }, {"r3.json", "spp", "lines 2 and 3"}},
      {"1 MiB unknown key", [&] { writeText(path("r4.json"), "{\"" + std::string(1 << 20, 'k') + "\": 1}");
         return "eia --run " + path("r4.json") + " --out " + out; }, {"r4.json", "(1048576 bytes)"}},
      // Rays that are not rays.
      {"NaN first ray in ray text", [&] { writeText(path("nan.txt"), "nan, 0, 0, 0, 0, 1\n0, 0, 0, 0, 0, 1\n");
         return "rays --in " + path("nan.txt") + " --out " + rays; }, {"nan.txt", "line 1"}},
      {"NUL inside a lens number", [&] { writeText(path("nul.dat"), std::string("29\0.475 3 1.5 20\n0 40 1 20\n", 27));
         return "lens info " + path("nul.dat"); }, {"nul.dat", "line 1", "a finite number"}},
      {"run file's triad wavelengths named as the file spells them", [&] {
         writeText(path("r6.json"), R"({"triad_wavelengths": "9999,500,600"})");
         return "eia --run " + path("r6.json") + " --out " + out; }, {"triad_wavelengths (", "r6.json"}},
      // Integers that wrapped, values no device has, placements that mirror.
      {"seed -1", [&] { return "eia --seed -1 --out " + out; }, {"--seed", "-1"}},
      {"seed 2^64", [&] { return "eia --seed 18446744073709551616 --out " + out; }, {"--seed", "18446744073709551616"}},
      {"scale -1", [&] { return "eia --scale -1 --out " + out; }, {"--scale", "-1"}},
      {"run scale -1", [&] { writeText(path("r5.json"), R"({"placement": {"scale": -1}})");
         return "eia --run " + path("r5.json") + " --out " + out; }, {"r5.json", "placement.scale"}},
      {"spp 2^31", [&] { return "eia --spp 2147483648 --out " + out; }, {"--spp"}},
      {"view height 1e6", [&] { return "view --eia " + out + " --height 1e6 --out " + out; }, {"--height", "1e+06"}},
      {"100,000-pixel panel", [&] { return "rays --display " + displayWithPanel("d2.json", "resolution_px", "[100000") + " --out " + rays; },
       {"resolution_px", "[1, 32768]"}},
      {"luminance 1e308", [&] { return "rays --display " + displayWithPanel("d3.json", "peak_luminance_cd_m2", "1e308") + " --out " + rays; },
       {"peak_luminance_cd_m2"}},
      {"train time budget NaN", [&] { return "train --data " + path("nowhere") + " --time-budget-s nan --out " + path("m.inimrf"); },
       {"--time-budget-s", "nan"}},
      // Commands and hosts.
      {"unknown command", [&] { return "eai --out " + out; }, {"unknown command 'eai'", "did you mean 'eia'"}},
      {"host 999.1.1.1", [&] { return "place --host 999.1.1.1 --port 0 --out " + path("place"); }, {"--host", "999.1.1.1"}},
      {"host 256.0.0.0", [&] { return "place --host 256.0.0.0 --port 0 --out " + path("place"); }, {"--host", "256.0.0.0"}},
      // Outputs.
      {"output link loop", [&] { return "rays --out " + linkTo("outloop.irays", path("outloop.irays")); }, {"outloop.irays", "a loop of symbolic links"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string args = c.args();
    const CliResult r = runInim(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("inim: error:"), std::string::npos) << r.output;
    for (const auto& n : c.needles) EXPECT_NE(r.output.find(n), std::string::npos) << "lacks '" << n << "':\n" << r.output;
    EXPECT_LT(r.output.size(), 2000u) << "one short message";
    EXPECT_FALSE(fs::exists(out) && fs::is_regular_file(out)) << c.name << " wrote " << out;
  }
}

TEST(CliHardening, OutputThroughALinkWritesItsTargetAndKeepsTheLink) {
  const std::string target = path("target.irays");
  writeText(target, "old");
  const std::string link = linkTo("link.irays", target);
  const CliResult r = runInim("rays --display " + data("optics/displays/paper-prototype.json") + " --out " + link);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_GT(fs::file_size(target), 1000u);
}
