// The settings table (core/settings_table.h): every entry well formed, scoped look-ups falling
// back to the general entry, ranges that refuse what no device has, and docs/settings.md equal
// to the table.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/settings_table.h"

using namespace inim;

TEST(SettingsTable, EntriesAreWellFormedAndUnique) {
  std::set<std::string> seen;
  for (const SettingInfo& s : settingsTable()) {
    const std::string id = std::string(s.key) + "@" + std::string(s.scope);
    EXPECT_TRUE(seen.insert(id).second) << "twice: " << id;
    EXPECT_FALSE(s.help.empty()) << id;
    EXPECT_EQ(s.key.find('-'), std::string_view::npos) << id << ": keys are snake_case";
    if (!std::isnan(s.lo)) {
      EXPECT_LE(s.lo, s.hi) << id;
      EXPECT_TRUE(std::isfinite(s.lo) && std::isfinite(s.hi)) << id;
      EXPECT_TRUE(s.choices.empty()) << id;
    }
    // A scoped entry refines a general one, or stands for a setting only that command has.
    if (!s.scope.empty()) {
      EXPECT_EQ(findSetting(s.key, s.scope), &s) << id;
    }
  }
}

TEST(SettingsTable, ScopedEntryWinsElseTheGeneralOne) {
  const SettingInfo* general = findSetting("spp");
  ASSERT_NE(general, nullptr);
  EXPECT_TRUE(general->scope.empty());
  EXPECT_EQ(findSetting("spp", "fig11")->scope, "fig11");
  EXPECT_EQ(findSetting("spp", "capture"), general);  // no capture entry: the general one
  EXPECT_EQ(findSetting("no_such_setting"), nullptr);
  EXPECT_EQ(settingFlag("viewing_distance_mm"), "--viewing-distance-mm");
}

TEST(SettingsTable, RangesRefuseWhatNoDeviceHas) {
  const SettingInfo& spp = *findSetting("spp");
  EXPECT_NO_THROW(checkSettingRange(spp, 1, "", "--spp"));
  EXPECT_NO_THROW(checkSettingRange(spp, spp.hi, "", "--spp"));
  for (double bad : {0.0, -1.0, spp.hi + 1, 1e308, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN(), 9.223372036854775808e18}) {
    try {
      checkSettingRange(spp, bad, "run.json", "spp");
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "run.json");
      EXPECT_EQ(e.key(), "spp");
      EXPECT_EQ(e.expected(), "a number in [1, 1048576]");
    }
  }
  // Angles within +-360 degrees, distances within 10 m, wavelengths in the visible.
  EXPECT_THROW(checkSettingRange(*findSetting("rot_h_deg"), 1e308, "", "--rot-h-deg"), InputError);
  EXPECT_THROW(checkSettingRange(*findSetting("distance_mm"), 2e4, "", "--distance-mm"), InputError);
  EXPECT_THROW(checkSettingRange(*findSetting("wavelength_nm"), 200, "", "--wavelength-nm"), InputError);
  // Subnormals and -0 are numbers like any other: inside the range or not by their value.
  EXPECT_NO_THROW(checkSettingRange(*findSetting("rot_v_deg"), -0.0, "", "--rot-v-deg"));
  EXPECT_THROW(checkSettingRange(spp, 4.9e-324, "", "--spp"), InputError);
}

TEST(SettingsTable, DocsListTheTable) {
  const std::string path = std::string(INIM_SOURCE_DATA_DIR) + "/docs/settings.md";
  std::ifstream in(path);
  std::stringstream doc;
  doc << in.rdbuf();
  if (doc.str() != settingsMarkdown()) {
    std::ofstream("settings.md") << settingsMarkdown();
    ADD_FAILURE() << "docs/settings.md differs from the settings table; the table's text is in "
                     "settings.md in the test's working folder: copy it over docs/settings.md";
  }
}

TEST(SettingsTable, EveryNumberReadFromAJsonFileHasARange) {
  // Every literal key a reader asks JsonObject for as a number: the table must give its range.
  const std::regex read(R"re(\.(number|positive|integer|integers|numbers|vec3)\("([A-Za-z0-9_]+)")re");
  int keys = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(INIM_SOURCE_DATA_DIR) + "/src")) {
    if (entry.path().extension() != ".cpp") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    for (std::sregex_iterator it(s.begin(), s.end(), read), end; it != end; ++it) {
      const std::string key = (*it)[2];
      const SettingInfo* info = findSetting(key, kFileScope);
      EXPECT_TRUE(info && !std::isnan(info->lo)) << entry.path().filename() << ": " << key << " has no range";
      ++keys;
    }
  }
  EXPECT_GT(keys, 80);
}
