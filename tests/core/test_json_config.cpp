#include <gtest/gtest.h>

#include "core/error.h"
#include "core/json_config.h"

using namespace inim;

TEST(JsonConfig, UnknownKeyNamesFileKeyAndValue) {
  Json j = Json::parse(R"({"radius_mm": 2, "raduis_mm": 3})");
  JsonObject o(j, "scene.json", "objects[0]");
  EXPECT_EQ(o.positive("radius_mm"), 2.0);
  try {
    o.rejectUnknown();
    FAIL() << "misspelt key accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    EXPECT_EQ(e.key(), "objects[0].raduis_mm");
    EXPECT_NE(std::string(e.what()).find("radius_mm"), std::string::npos);  // lists known keys
  }
}

TEST(JsonConfig, NonPositiveSizeRejected) {
  Json j = Json::parse(R"({"size_mm": -1, "zero": 0})");
  JsonObject o(j, "f.json", "");
  EXPECT_THROW(o.positive("size_mm"), InputError);
  EXPECT_THROW(o.positive("zero"), InputError);
  EXPECT_THROW(o.number("missing"), InputError);
}

TEST(JsonConfig, ChoiceListsAllowedValues) {
  Json j = Json::parse(R"({"type": "sphear"})");
  JsonObject o(j, "f.json", "objects[1]");
  try {
    o.choice("type", {"sphere", "box"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sphere, box"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("sphear"), std::string::npos);
  }
}

TEST(JsonConfig, MissingRequiredKeyPointsAtTheMisspelling) {
  Json j = Json::parse(R"({"raduis_mm": 3})");
  JsonObject o(j, "s.json", "objects[0]");
  try {
    o.positive("radius_mm");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("raduis_mm"), std::string::npos) << e.what();
  }
}
