// The error budget on a small noise-free case (the slanted-edge scene, direct lighting): the
// noise floor is below the reconstruction's error, the ideal display is never worse than the full chain beyond it, a rung
// that cannot be built is skipped with a note, and unknown rung names are bad input.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/output_file.h"
#include "expect_input_error.h"
#include "experiments/fig11.h"
#include "scratch_dir.h"

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
