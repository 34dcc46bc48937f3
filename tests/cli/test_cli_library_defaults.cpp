// The library and the command give the same result for the same call: `inim eia`, `inim rays`
// and `inim view` told nothing but their inputs and outputs write the same bytes as runEia,
// exportRays and runView called with settings left at their defaults. Defaults are written
// once, in the settings structs; the command line only overrides them.
#include <gtest/gtest.h>

#include <string>

#include "cli/run_cli.h"
#include "fixtures.h"
#include "runs/camera_run.h"
#include "runs/eia_run.h"
#include "runs/ray_export.h"

using namespace inim;

namespace {

fixtures::ScratchDir& scratch() {
  static fixtures::ScratchDir dir("test_cli_library_defaults");
  return dir;
}

const std::string& smallDisplay() {
  static const std::string path = [] {
    const std::string p = scratch().path("display.json");
    fixtures::writeBytes(p, fixtures::smallDisplayJson({11, 9, 9}));
    return p;
  }();
  return path;
}

void expectSameBytes(const std::string& a, const std::string& b) {
  const std::string x = fixtures::readBytes(a), y = fixtures::readBytes(b);
  ASSERT_FALSE(x.empty()) << a;
  EXPECT_TRUE(x == y) << a << " and " << b << " differ";
}

// The EIA of the default scene on the small display, as the command writes it.
const std::string& commandEia() {
  static const std::string out = [] {
    const std::string o = scratch().path("command.exr");
    const CliResult r = runInim("eia --display " + smallDisplay() + " --out " + o + " --quiet");
    EXPECT_EQ(r.status, 0) << r.output;
    return o;
  }();
  return out;
}

}  // namespace

TEST(LibraryDefaults, EiaCommandEqualsRunEiaAtItsDefaults) {
  EiaRunSettings s;
  s.displayPath = smallDisplay();
  s.out = scratch().path("library.exr");
  s.synthesis.progress = false;
  (void)runEia(s);
  expectSameBytes(commandEia(), s.out);
  expectSameBytes(scratch().path("command.png"), scratch().path("library.png"));
}

TEST(LibraryDefaults, RaysCommandEqualsExportRaysAtItsDefaults) {
  for (const bool forField : {false, true}) {
    const std::string ext = forField ? ".npy" : ".irays";
    const std::string cmdOut = scratch().path("command-rays" + ext);
    const CliResult r =
        runInim("rays --display " + smallDisplay() + (forField ? " --for-field" : "") + " --out " + cmdOut);
    ASSERT_EQ(r.status, 0) << r.output;
    RayExportSettings s;
    s.displayPath = smallDisplay();
    s.forField = forField;
    s.out = scratch().path("library-rays" + ext);
    (void)exportRays(s);
    expectSameBytes(cmdOut, s.out);
  }
}

TEST(LibraryDefaults, ViewCommandEqualsRunViewAtItsDefaults) {
  const std::string cmdOut = scratch().path("command-view.exr");
  const CliResult r = runInim("view --display " + smallDisplay() + " --eia " + commandEia() + " --width 40 --out " +
                              cmdOut + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  ViewRunSettings s;
  s.displayPath = smallDisplay();
  s.eiaPath = commandEia();
  s.camera.width = 40;
  s.camera.out = scratch().path("library-view.exr");
  s.view.progress = false;
  (void)runView(s, {});
  expectSameBytes(cmdOut, s.camera.out);
  expectSameBytes(scratch().path("command-view.png"), scratch().path("library-view.png"));
}
