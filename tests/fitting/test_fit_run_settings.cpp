// The training and evaluation settings given as text: grid stage lists and the background.
#include "fitting/fit_run.h"

#include <gtest/gtest.h>

#include "fixtures.h"

using namespace inim;
using fixtures::expectInputError;

TEST(FitRunSettings, IntListsAreWholeNumbersSeparatedByCommas) {
  EXPECT_EQ(parseIntList("64,128,160", "resolutions"), (std::vector<int>{64, 128, 160}));
  EXPECT_EQ(parseIntList("0", "stage_starts"), (std::vector<int>{0}));
  for (const char* bad : {"", "64,", ",64", "64,x", "1.5"})
    EXPECT_EQ(expectInputError([&] { (void)parseIntList(bad, "resolutions"); }).key(), "resolutions") << bad;
}

TEST(FitRunSettings, BackgroundIsWhiteBlackOrAColourInTheUnitCube) {
  EXPECT_EQ(parseBackground("white"), glm::vec3(1.0f));
  EXPECT_EQ(parseBackground("black"), glm::vec3(0.0f));
  EXPECT_EQ(parseBackground("0.25,0.5,1"), glm::vec3(0.25f, 0.5f, 1.0f));
  for (const char* bad : {"2,0,0", "-0.1,0,0", "grey", "0.5,0.5"})
    EXPECT_EQ(expectInputError([&] { (void)parseBackground(bad); }).key(), "background") << bad;
}
