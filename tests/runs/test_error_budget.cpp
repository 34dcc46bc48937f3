// The error budget on a small noise-free case (the slanted-edge scene, direct lighting): the
// noise floor is below the reconstruction's error, the ideal display is never worse than the full chain beyond it, a rung
// that cannot be built is skipped with a note, and unknown rung names are bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <tuple>

#include "camera/camera_config.h"
#include "colour_chain/chain_response.h"
#include "core/output_file.h"
#include "core/rng.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "expect_input_error.h"
#include "runs/fig11.h"
#include "scratch_dir.h"
#include "display_view/display_model.h"
#include "display_view/view_camera.h"
#include "display_view/view_renderer.h"

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

// A stack display with aperture sheets or barrier walls gets one rung per such layer kind after
// the real MLA, which then refracts without them, and their removals; other displays keep the
// ladder of today (the default display's budget files stay the same).
TEST(ErrorBudget, AStacksSheetsAndWallsGetARungEach) {
  auto names = [](const std::vector<BudgetRung>& rungs) {
    std::string s;
    for (const BudgetRung& r : rungs) s += r.name + " ";
    return s;
  };
  const Display paper = loadDisplay(displayPathOrDefault(""));
  EXPECT_EQ(names(budgetRungs(&paper)), names(budgetRungs()));
  const Display barrier = loadDisplay(dataPath("optics/displays/barrier-mla.json"));
  const std::vector<BudgetRung> b = budgetRungs(&barrier);
  EXPECT_EQ(names(b),
            "ideal +subpixels +real_mla +barriers +cover_glass +colour_chain +calibration -subpixels -real_mla "
            "-cover_glass -colour_chain -barriers ");
  EXPECT_FALSE(b[2].barriers);  // + real MLA: the lenses without the walls
  EXPECT_TRUE(b[3].barriers && b[3].realMla && !b[3].coverGlass);
  EXPECT_TRUE(b[4].barriers);
  EXPECT_FALSE(b.back().barriers);
  EXPECT_TRUE(b.back().coverGlass && b.back().colourChain && b.back().removal);
  const Display compound = loadDisplay(dataPath("optics/displays/compound-symmetric.json"));
  const std::vector<BudgetRung> c = budgetRungs(&compound);
  EXPECT_EQ(c[3].name, "+apertures");
  EXPECT_FALSE(c[2].apertures);
  EXPECT_EQ(c.back().name, "-apertures");
  // Their names are valid before a display is known and select nothing on a display without them.
  EXPECT_TRUE(selectRungs({"+barriers"}, &paper).empty());
  EXPECT_EQ(selectRungs({"-barriers", "ideal"}, &barrier).size(), 2u);
}

// The default display showing random drive values (every channel matters everywhere), seen at
// 0 deg by the default camera at 40 px, rendered at 1 stratum on a 4 x 4 aperture grid.
struct RandomDriveScene {
  Display d = loadDisplay(displayPathOrDefault(""));
  EiLayout layout = computeLayout(d);
  Image eia;
  DisplayModel dm;
  CameraDescription cam = loadCameraDescription("alvium-1800-u-500c");
  std::unique_ptr<CameraModel> camera;
  ViewSettings vs;
  explicit RandomDriveScene(uint64_t seed) : eia(layout.eiaW, layout.eiaH, {"R", "G", "B"}) {
    Rng rng(seed, 0);
    for (float& v : eia.data) v = rng.uniform();
    dm = makeDisplayModel(d, layout, eia, "(random)", MlaKind::Real);
    ViewCameraOptions co;
    co.width = 40;
    camera = makeViewCamera(cam, DisplayPose{}, co);
    vs.spp = 1;
    vs.apertureGrid = 4;
    vs.progress = false;
  }
};

// The budget shares one render between rungs that differ only by the colour chain: the
// observer's view must be the camera's view through sensorSwap, pixel by pixel (real MLA,
// cover glass, subpixels; random drive values so that every channel matters everywhere).
TEST(ErrorBudget, TheObserversViewIsTheCamerasViewThroughTheSensorSwap) {
  const RandomDriveScene r(7);
  const auto& [dm, cam, camera, vs] = std::tie(r.dm, r.cam, r.camera, r.vs);
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

// The rungs that differ from the full chain in the panel only (no subpixels; the calibrated EIA)
// can be carried by the full chain's render (fullChainCompanions, renderViews): the budget is
// then the same, rung for rung and bit for bit, as when each rung renders itself.
TEST(ErrorBudget, RungsCarriedByTheViewAreTheRungsRenderedAlone) {
  const RandomDriveScene r(11);
  const auto& [dm, cam, camera, vs] = std::tie(r.dm, r.cam, r.camera, r.vs);
  Image calibrated = r.eia;
  for (float& v : calibrated.data) v *= 0.8f;
  Rng rng(12, 0);
  const BudgetScene scene{&r.d, &r.layout, &r.eia, &calibrated, &cam, vs, 0.0};
  const std::vector<RungPanel> companions = fullChainCompanions(scene, budgetRungs(), dm.gapMm, dm.panel->driveTable());
  ASSERT_EQ(companions.size(), 2u);
  EXPECT_EQ(companions[0].rung.name, "+calibration");
  EXPECT_EQ(companions[1].rung.name, "-subpixels");
  std::vector<const PanelEmitter*> panels{dm.panel.get()};
  for (const RungPanel& p : companions) panels.push_back(p.panel.get());
  const std::vector<ViewResult> views = renderViews(*camera, cam.sensor, *dm.mla, panels, dm.area, vs);
  ASSERT_TRUE(views[1].carried && views[2].carried);
  std::vector<MadeRungView> made{{fullChainRung(), &views[0].image, ""}};
  for (size_t k = 0; k < companions.size(); ++k) made.push_back({companions[k].rung, &views[k + 1].image, "carried"});

  // Exposed as fig11 exposes: the full chain's peak at 0.5.
  float peak = 0.0f;
  for (float v : views[0].image.data) peak = std::max(peak, v);
  ASSERT_GT(peak, 0.0f);
  const double exposure = 0.5 / peak;
  Image reference = views[0].image, second = views[0].image;
  for (size_t i = 0; i < reference.data.size(); ++i) {
    reference.data[i] *= float(exposure) * (1.0f + 0.2f * rng.uniform());
    second.data[i] *= float(exposure);
  }
  PixelMask mask;
  mask.width = reference.width, mask.height = reference.height;
  mask.on.assign(size_t(mask.width) * mask.height, 1);
  const PoseBudget alone = poseBudget(scene, *camera, reference, second, exposure, mask, budgetRungs());
  const PoseBudget carried = poseBudget(scene, *camera, reference, second, exposure, mask, budgetRungs(), made);
  auto expectSame = [](const std::vector<RungResult>& a, const std::vector<RungResult>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].skipped, b[i].skipped) << a[i].rung.name;
      EXPECT_EQ(a[i].metrics.psnrDb, b[i].metrics.psnrDb) << a[i].rung.name;
      EXPECT_EQ(a[i].metrics.deltaE.mean, b[i].metrics.deltaE.mean) << a[i].rung.name;
      EXPECT_EQ(a[i].metrics.ssim, b[i].metrics.ssim) << a[i].rung.name;
    }
  };
  expectSame(alone.ladder, carried.ladder);
  expectSame(alone.removeOne, carried.removeOne);
  // The calibrated EIA is another view, so the calibration rung moved the error.
  EXPECT_NE(carried.ladder[5].metrics.deltaE.mean, carried.ladder[4].metrics.deltaE.mean);
  EXPECT_EQ(carried.ladder[5].note, "carried");
  // Without the view's pass, the ideal display and + subpixels share one (the ideal MLA, no glass).
  EXPECT_NE(alone.ladder[1].note.find("rendered in one pass with ideal"), std::string::npos) << alone.ladder[1].note;
}
