#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/json_config.h"
#include "core/size_budget.h"
#include "fixtures.h"

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

// ---------------------------------------------------------------------------------------
// Parsing: every reader goes through readJsonFile, which refuses what the library takes badly.

namespace {

// A file in the temporary folder holding `text`, removed with the object.
struct TempJson {
  std::string path;
  TempJson(const std::string& name, const std::string& text)
      : path((std::filesystem::temp_directory_path() /
              ("inim_json_" + std::to_string(::getpid()) + "_" + name)).string()) {
    std::ofstream(path, std::ios::binary) << text;
  }
  ~TempJson() { std::filesystem::remove(path); }
};

using fixtures::expectInputError;

std::string nested(int levels) { return std::string(size_t(levels), '[') + std::string(size_t(levels), ']'); }

}  // namespace

TEST(JsonConfig, DeepNestingRefusedWhileParsingNamingTheFile) {
  // 100,000 levels used to overflow the stack (exit 139) as soon as anything printed or
  // copied the value; 10,000 too is far beyond any config.
  for (int levels : {100000, 10000, kMaxJsonDepth + 1}) {
    TempJson f("deep.json", nested(levels));
    InputError e = expectInputError([&] { readJsonFile(f.path); });
    EXPECT_EQ(e.file(), f.path);
    EXPECT_NE(std::string(e.what()).find("nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels"),
              std::string::npos) << e.what();
  }
  // At the limit, objects and arrays alike, it is read.
  TempJson ok("limit.json", std::string(size_t(kMaxJsonDepth - 1), '[') + "{}" +
                                std::string(size_t(kMaxJsonDepth - 1), ']'));
  Json j = readJsonFile(ok.path);
  EXPECT_TRUE(j.is_array());
}

TEST(JsonConfig, ValueTextOfADeepValueIsBounded) {
  // Built in code (no parser limit): the message text must still not recurse per level.
  Json j = Json::array();
  for (int i = 0; i < 100000; ++i) {
    Json outer = Json::array();
    outer.push_back(std::move(j));
    j = std::move(outer);
  }
  const std::string s = jsonValueText(j);
  EXPECT_EQ(s, std::string(57, '[') + "...");
  // Small values print as the library prints them.
  Json small = Json::parse(R"({"a": [1, 2.5, "x"], "b": null})");
  EXPECT_EQ(jsonValueText(small), small.dump());
}

TEST(JsonConfig, NumberBeyondADoubleNamesFileValueAndLine) {
  TempJson f("huge.json", "{\n  \"name\": \"x\",\n  \"gap_mm\": 1e400\n}\n");
  InputError e = expectInputError([&] { readJsonFile(f.path); });
  EXPECT_EQ(e.file(), f.path);
  const std::string msg = e.what();
  EXPECT_NE(msg.find("1e400"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 3, column 13"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("json.exception"), std::string::npos) << "raw library message: " << msg;
}

TEST(JsonConfig, CommentsAreRefused) {
  TempJson f("comment.json", "{\n  // the prototype\n  \"name\": \"x\"\n}\n");
  InputError e = expectInputError([&] { readJsonFile(f.path); });
  EXPECT_EQ(e.file(), f.path);
  EXPECT_NE(std::string(e.what()).find("comment (line 2, column 3)"), std::string::npos) << e.what();
  TempJson block("block.json", "{\"name\": /* x */ \"x\"}");
  EXPECT_THROW(readJsonFile(block.path), InputError);
}

TEST(JsonConfig, MalformedJsonNamesFileAndPosition) {
  TempJson f("bad.json", "{\"a\": 1,\n \"b\": }");
  InputError e = expectInputError([&] { readJsonFile(f.path); });
  EXPECT_EQ(e.file(), f.path);
  EXPECT_NE(std::string(e.what()).find("line 2, column 7"), std::string::npos) << e.what();
}

// ---------------------------------------------------------------------------------------
// Whole numbers are read exactly.

TEST(JsonConfig, IntegersNeverWrap) {
  Json j = Json::parse(R"({"spp": 4294967297, "count": 4294967304, "big": 1e12, "neg": -4294967295,
                           "int_max": 2147483647, "int_min": -2147483648, "over": 2147483648, "u64": 18446744073709551615})");
  JsonObject o(j, "run.json", "");
  for (const char* key : {"spp", "count", "big", "neg", "over", "u64"}) {
    InputError e = expectInputError([&] { o.integer(key); });
    EXPECT_EQ(e.file(), "run.json");
    EXPECT_EQ(e.key(), key);
    EXPECT_EQ(e.value(), j[key].dump()) << "the value as written";
  }
  // Keys the settings table does not know keep only the call's own range (here int's).
  EXPECT_EQ(o.integer("int_max"), 2147483647);
  EXPECT_EQ(o.integer("int_min"), -2147483648);
  // A range check sees the value itself: 4294967304 is not 8.
  InputError e = expectInputError([&] { o.integer("count", 0, 1000); });
  EXPECT_EQ(e.value(), "4294967304");
  EXPECT_NE(e.expected().find("[0, 1000]"), std::string::npos) << e.expected();
}

TEST(JsonConfig, WholeFloatsAreIntegersFractionsAreNot) {
  Json j = Json::parse(R"({"w": 1080.0, "h": 1080.5, "z": -0.0, "size": [1920.0, 1080], "bad": [4, 2.5]})");
  JsonObject o(j, "transforms.json", "");
  EXPECT_EQ(o.integer("w"), 1080);
  EXPECT_EQ(o.integer("z"), 0);
  InputError e = expectInputError([&] { o.integer("h"); });
  EXPECT_EQ(e.key(), "h");
  EXPECT_EQ(e.value(), "1080.5");
  EXPECT_EQ(o.integers("size", 1, 100000), (std::vector<int>{1920, 1080}));
  EXPECT_THROW(o.integers("bad", 1, 100000), InputError);
  EXPECT_THROW(o.integer("w", 1, 1000), InputError);  // in range only up to 1000
}

TEST(JsonConfig, NonFiniteNumbersRefused) {
  // JSON text cannot hold them, but a value built in code can.
  Json j = {{"nan", std::nan("")}, {"inf", HUGE_VAL}, {"v", {1.0, HUGE_VAL, 0.0}}, {"n", {-HUGE_VAL}}};
  JsonObject o(j, "f.json", "");
  EXPECT_THROW(o.number("nan"), InputError);
  EXPECT_THROW(o.number("inf"), InputError);
  EXPECT_THROW(o.positive("inf"), InputError);
  EXPECT_THROW(o.integer("inf"), InputError);
  EXPECT_THROW(o.integer("nan"), InputError);
  EXPECT_THROW(o.vec3("v"), InputError);
  EXPECT_THROW(o.numbers("n"), InputError);
}

TEST(JsonConfig, DuplicateKeysAreRefusedWithBothLines) {
  const std::string text = "{\n  \"a\": 1,\n  \"panel\": {\"x\": 1,\n    \"x\": 2},\n  \"b\": 3\n}\n";
  try {
    parseJsonText(text, "d.json");
    FAIL() << "duplicate key accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "d.json");
    EXPECT_EQ(e.key(), "x");
    EXPECT_EQ(e.value(), "given twice (lines 3 and 4)");
  }
  // The same key in different objects, or the same text as a value, is not a duplicate.
  EXPECT_NO_THROW(parseJsonText(R"({"a": {"x": 1}, "b": {"x": 2}, "c": "x", "x": "a"})", "ok.json"));
  // Top-level duplicates after nested objects are still seen.
  EXPECT_THROW(parseJsonText(R"({"k": {"k": 1}, "k": 2})", "top.json"), InputError);
}

// A small file that expands: 300 kB of "{}" is 100,000 objects, several MiB once parsed. The
// parser counts what it builds and stops at the memory limit, naming the file.
TEST(JsonConfig, ADocumentLargerThanTheMemoryLimitOnceParsedIsRefused) {
  std::string text = "[";
  for (int i = 0; i < 100000; ++i) text += i ? ",{}" : "{}";
  text += "]";
  {
    ScopedMemoryLimit limit(4u << 20);
    try {
      parseJsonText(text, "many.json");
      FAIL() << "a document of 100,000 objects parsed within 4 MiB";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "many.json");
      EXPECT_NE(e.value().find("once parsed"), std::string::npos) << e.value();
      EXPECT_NE(e.expected().find("--max-memory"), std::string::npos) << e.expected();
    }
  }
  ScopedMemoryLimit roomy(64u << 20);
  EXPECT_EQ(parseJsonText(text, "many.json").size(), 100000u);
}

TEST(JsonConfig, LongKeysAndValuesAreTruncatedWithTheirLength) {
  const std::string key(1 << 20, 'k');
  Json j = parseJsonText("{\"" + key + "\": 1}", "long.json");
  JsonObject o(j, "long.json", "");
  try {
    o.rejectUnknown();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), 1000u);
    EXPECT_NE(e.key().find("(1048576 bytes)"), std::string::npos) << e.key();
  }
}

TEST(JsonConfig, InvalidUtf8IsEchoedAsValidText) {
  Json j = Json::object();
  j["layout"] = std::string("\xff\xfe", 2);
  EXPECT_NO_THROW(jsonValueText(j));
  const std::string text = jsonText(j);
  EXPECT_NE(text.find("\xef\xbf\xbd"), std::string::npos) << text;  // U+FFFD
}

TEST(JsonConfig, NumbersOutsideTheirKeysRangeNameKeyValueAndRange) {
  Json j = parseJsonText(R"({"panel": {"pixel_pitch_mm": 9.223372036854775808e18, "gamma": 2.2}})", "p.json");
  const JsonObject panel = JsonObject(j, "p.json", "").object("panel");
  EXPECT_EQ(panel.positive("gamma"), 2.2);
  try {
    panel.positive("pixel_pitch_mm");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "p.json");
    EXPECT_EQ(e.key(), "panel.pixel_pitch_mm");
    EXPECT_EQ(e.expected(), "a number in [0.0001, 10]");
  }
  // Each element of an array, and whole numbers too.
  Json v = parseJsonText(R"({"rotate_deg": [0, 1e308, 0], "resolution_px": [100000, 10]})", "v.json");
  EXPECT_THROW(JsonObject(v, "v.json", "").vec3("rotate_deg"), InputError);
  EXPECT_THROW(JsonObject(v, "v.json", "").integers("resolution_px", 1, 1 << 30), InputError);
}
