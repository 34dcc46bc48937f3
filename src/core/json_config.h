#pragma once
// Strict JSON config access: every read names its file and key path, every key must be
// consumed, so a misspelt key is an error instead of a silently ignored setting. Every JSON
// file the program reads goes through readJsonFile, which refuses what the library would take
// badly: nesting deeper than kMaxJsonDepth (the library's printer and copier recurse),
// numbers too large for a double, and comments (not JSON).
//
//   Json j = readJsonFile(path);
//   JsonObject o(j, path, "");
//   int spp = o.integer("spp", 1, 1 << 20);  // exact: 4294967297 or 2.5 is an error, not 1 or 2
//   o.rejectUnknown();
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace inim {

using Json = nlohmann::json;

// Deeper nesting than any config needs; refused while parsing, before it can hurt.
constexpr int kMaxJsonDepth = 512;

// Parses a JSON file; throws InputError naming the file (and line/column) on malformed JSON,
// comments, nesting deeper than kMaxJsonDepth, or a number too large for a double.
Json readJsonFile(const std::string& path);
// The same for text held in memory; `name` stands for the file in messages.
Json parseJsonText(const std::string& text, const std::string& name);

class JsonObject {
 public:
  // `path` is the key path of this object inside `file`, e.g. "objects[3].material".
  JsonObject(const Json& j, std::string file, std::string path);

  bool has(const std::string& key) const;
  const Json& raw(const std::string& key) const;  // throws if missing

  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  double positive(const std::string& key) const;  // > 0
  double positive(const std::string& key, double fallback) const;
  // A whole number: an integer, or a number with a fraction part of zero (1080.0, as some
  // tools write sizes), in [lo, hi] (default: int's range). The value is read exactly: 1080.5,
  // 1e12 or 4294967297 is an error naming it as written, never rounded or wrapped.
  int integer(const std::string& key) const;
  int integer(const std::string& key, int fallback) const;
  int integer(const std::string& key, int lo, int hi) const;
  // An array of whole numbers, each in [lo, hi].
  std::vector<int> integers(const std::string& key, int lo, int hi) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  // One of `allowed`, else an error listing them.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& fallback) const;
  Vec3d vec3(const std::string& key) const;
  Vec3d vec3(const std::string& key, const Vec3d& fallback) const;
  std::vector<double> numbers(const std::string& key) const;
  JsonObject object(const std::string& key) const;
  std::vector<JsonObject> objects(const std::string& key) const;  // an array of objects
  // A file path relative to this config file's folder.
  std::string path(const std::string& key) const;

  // Throws for any key not read so far (the first, alphabetically), naming known keys.
  void rejectUnknown() const;
  // Throws an InputError for `key` with the given value text and expectation.
  [[noreturn]] void fail(const std::string& key, const std::string& value,
                         const std::string& expected) const;

  const std::string& file() const { return file_; }
  const std::string& keyPath() const { return path_; }
  std::string keyPath(const std::string& key) const;
  const Json& json() const { return j_; }

 private:
  const Json& get(const std::string& key) const;
  void checkRange(const std::string& key, double v, const Json* array = nullptr) const;
  std::string closestKey(const std::string& key) const;  // a present key within 2 edits
  const Json& j_;
  std::string file_, path_;
  mutable std::set<std::string> used_;   // keys present and read
  mutable std::set<std::string> asked_;  // keys the reader knows, present or not
};

// Compact JSON text that is valid UTF-8 whatever the strings hold (invalid bytes become
// U+FFFD): answers that echo a client's bytes never fail to print.
std::string jsonText(const Json& j);

// Compact, truncated to 60 characters, for messages; bounded work and stack at any depth.
std::string jsonValueText(const Json& j);

}  // namespace inim
