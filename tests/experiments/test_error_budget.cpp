// The error budget on a small noise-free case (the slanted-edge scene, direct lighting): the
// noise floor is below the reconstruction's error, the ideal display is never worse than the full chain beyond it, a rung
// that cannot be built is skipped with a note, and unknown rung names are bad input.
#include <gtest/gtest.h>

#include <filesystem>

#include "camera/camera_config.h"
#include "colour_chain/chain_response.h"
#include "core/output_file.h"
#include "core/rng.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "expect_input_error.h"
#include "experiments/fig11.h"
#include "scratch_dir.h"
#include "view/display_model.h"
#include "view/view_camera.h"
#include "view/view_renderer.h"

using namespace inim;
namespace fs = std::filesystem;

namespace {
ScratchDir scratch("error_budget");
}

TEST(ErrorBudget, IdealDisplayIsNeverWorseThanTheFullChainBeyondTheNoiseFloor) {
  Fig11Settings s;
  s.outDir = scratch.path("budget");
  s.fieldPath = dataPath("scenes/test/slanted-edge.json");
  s.width = 96;
  s.spp = 1;
  s.referenceSpp = 4;
  s.eiaSpp = 1;
  s.budget = true;
  s.budgetRungs = {"ideal", "+colour_chain", "+calibration", "-real_mla"};
  const Fig11Result r = runFig11(s);
  ASSERT_EQ(r.budgets.size(), 5u);
  for (const PoseBudget& b : r.budgets) {
    ASSERT_EQ(b.ladder.size(), 3u);
    const RungResult &ideal = b.ladder[0], &full = b.ladder[1], &calibrated = b.ladder[2];
    const double floor = b.noiseFloor.deltaE.mean;
    // Direct lighting: two seeds differ only where pixels straddle the targets' edges (4 samples).
    EXPECT_GT(floor, 0.0) << b.pose;
    EXPECT_LT(floor, full.metrics.deltaE.mean) << b.pose;
    EXPECT_LE(ideal.metrics.deltaE.mean, full.metrics.deltaE.mean + floor) << b.pose;
    ASSERT_TRUE(idealWithinFloorOfFullChain(b).has_value());
    EXPECT_TRUE(*idealWithinFloorOfFullChain(b)) << b.pose;
    EXPECT_TRUE(calibrated.skipped);
    EXPECT_NE(calibrated.note.find("calibration"), std::string::npos);
    ASSERT_EQ(b.removeOne.size(), 1u);
    EXPECT_FALSE(b.removeOne[0].skipped);
  }
  for (const char* f : {"budget.json", "budget.csv", "budget.png"}) EXPECT_TRUE(fs::exists(fs::path(s.outDir) / f)) << f;
}

TEST(ErrorBudget, UnknownRungNamesListTheValidOnes) {
  const InputError e = expectInputError([] { selectRungs({"ideal", "+sparkle"}); });
  EXPECT_EQ(e.key(), "budget_rungs");
  EXPECT_NE(e.expected().find("+real_mla"), std::string::npos);
  EXPECT_EQ(selectRungs({"-cover_glass"}).at(0).coverGlass, false);
}

// The budget shares one render between rungs that differ only by the colour chain: the
// observer's view must be the camera's view through sensorSwap, pixel by pixel (real MLA,
// cover glass, subpixels; random drive values so that every channel matters everywhere).
TEST(ErrorBudget, TheObserversViewIsTheCamerasViewThroughTheSensorSwap) {
  const Display d = loadDisplay(displayPathOrDefault(""));
  const EiLayout layout = computeLayout(d);
  Image eia(layout.eiaW, layout.eiaH, {"R", "G", "B"});
  Rng rng(7, 0);
  for (float& v : eia.data) v = rng.uniform();
  const DisplayModel dm = makeDisplayModel(d, layout, eia, "(random)", MlaKind::Real);
  const CameraDescription cam = loadCameraDescription("alvium-1800-u-500c");
  ViewCameraOptions co;
  co.width = 40;
  const auto camera = makeViewCamera(cam, DisplayPose{}, co);
  ViewSettings vs;
  vs.spp = 1;
  vs.apertureGrid = 4;
  vs.progress = false;
  ASSERT_TRUE(sensorSwapIsExact(vs));
  const CameraSensor observer = cieObserverSensor(cam.sensor.geometry());
  const Image seenByCamera = renderView(*camera, cam.sensor, *dm.mla, *dm.panel, dm.area, vs).image;
  const Image seenByObserver = renderView(*camera, observer, *dm.mla, *dm.panel, dm.area, vs).image;
  const Image swapped = transformedRgb(seenByCamera, sensorSwap(*dm.panel, cam.sensor, observer));
  float peak = 0.0f;
  for (float v : seenByObserver.data) peak = std::max(peak, std::abs(v));
  ASSERT_GT(peak, 0.0f);
  double worst = 0.0;
  for (size_t i = 0; i < swapped.data.size(); ++i)
    worst = std::max(worst, double(std::abs(swapped.data[i] - seenByObserver.data[i])));
  EXPECT_LT(worst / peak, 1e-5);  // float accumulation only
}
