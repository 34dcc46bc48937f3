#include "core/json_config.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/input_file.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/settings_table.h"
#include "core/size_budget.h"

namespace inim {

namespace {

// "line L, column C" (1-based) of byte `offset` in `text`.
std::string lineColumn(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  const size_t lines = size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(offset), '\n'));
  const size_t lineStart = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
  const size_t column = lineStart == std::string::npos ? offset + 1 : offset - lineStart;
  return "line " + std::to_string(lines + 1) + ", column " + std::to_string(column);
}

// A key or value as messages quote it: whole up to 60 bytes, else its start and its length.
std::string messageText(const std::string& text) {
  if (text.size() <= 60) return text;
  size_t cut = 48;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // whole UTF-8 characters
  return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " bytes)";
}

struct DuplicateKeySeen {};

// The library's own DOM builder, with the nesting counted as it goes (its parser is
// iterative, but printing and copying a value recurse, so a deep file would overflow the
// stack later) and every parse failure turned into an InputError naming the file and where.
class CheckedSax {
 public:
  // Without `locateKeys` a duplicate key throws DuplicateKeySeen: finding the line of every
  // key costs a search of the text each, so only a second pass over a file that has a
  // duplicate does it, to name both lines.
  CheckedSax(Json& root, const std::string& text, const std::string& name, bool locateKeys)
      : dom_(root), text_(text), name_(name), locateKeys_(locateKeys) {}

  bool null() { return account(kValueBytes), dom_.null(); }
  bool boolean(bool v) { return account(kValueBytes), dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return account(kValueBytes), dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return account(kValueBytes), dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const std::string& s) {
    return account(kValueBytes), dom_.number_float(v, s);
  }
  bool string(std::string& v) { return account(kValueBytes + heapTextBytes(v)), dom_.string(v); }
  bool binary(Json::binary_t& v) { return account(kValueBytes + double(v.size())), dom_.binary(v); }
  bool key(std::string& k) {
    account(kMemberBytes + heapTextBytes(k));
    const size_t line = locateKeys_ ? lineOfKey(k) : 0;
    if (auto [it, added] = keys_[open_ - 1].emplace(k, line); !added) {
      if (!locateKeys_) throw DuplicateKeySeen{};
      throw InputError(name_, messageText(k), "given twice (lines " + std::to_string(it->second) + " and " +
                                                  std::to_string(line) + ")",
                       "each key once in an object (a later one would silently replace the first)");
    }
    return dom_.key(k);
  }
  bool start_object(std::size_t n) {
    if (!enter()) return false;
    account(kValueBytes + kContainerBytes);
    // The maps of closed objects are reused (no allocation per object), but not a large one:
    // clearing costs its bucket count.
    if (open_ == keys_.size()) keys_.emplace_back();
    auto& keys = keys_[open_++];
    if (keys.bucket_count() > 64) keys = {};
    keys.clear();
    return dom_.start_object(n);
  }
  bool end_object() { return --depth_, --open_, dom_.end_object(); }
  bool start_array(std::size_t n) { return enter() && (account(kValueBytes + kContainerBytes), dom_.start_array(n)); }
  bool end_array() { return --depth_, dom_.end_array(); }

  // `offset` is the byte just past the offending token; `token` is that number for 406.
  bool parse_error(std::size_t offset, const std::string& token, const Json::exception& e) {
    if (e.id == 406)  // a number literal beyond a double's range
      throw InputError(name_, "", token + " (" + lineColumn(text_, offset - std::min(offset, token.size())) + ")",
                       "a finite number (within a double's range, |x| < 1.8e308)");
    if (offset >= 1 && offset <= text_.size() && text_[offset - 1] == '/')  // the lexer stops at the '/'
      throw InputError(name_, "", "a comment (" + lineColumn(text_, offset - 1) + ")",
                       "JSON without comments (notes go in a key starting with '_', e.g. \"_comment\")");
    throw InputError(name_, "", "malformed JSON (" + std::string(e.what()) + ")", "valid JSON");
  }

 private:
  bool enter() {
    throwIfInterrupted();  // a file of a million objects still stops at once on Ctrl-C
    if (++depth_ > kMaxJsonDepth)
      throw InputError(name_, "", "nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels",
                       "JSON nested at most " + std::to_string(kMaxJsonDepth) + " levels deep");
    return true;
  }
  // The line of key `k`: the keys come in the order of the text, so each is searched for from
  // the previous one on (as written: "k" then ':'); 0 when it is spelt with escapes.
  size_t lineOfKey(const std::string& k) {
    const bool plain = std::none_of(k.begin(), k.end(), [](char c) { return c == '"' || c == '\\' || uint8_t(c) < 0x20; });
    const std::string quoted = plain ? "\"" + k + "\"" : jsonText(Json(k));  // as the file spells it
    for (size_t at = text_.find(quoted, cursor_); at != std::string::npos; at = text_.find(quoted, at + 1)) {
      const size_t after = text_.find_first_not_of(" \t\r\n", at + quoted.size());
      if (after == std::string::npos || text_[after] != ':') continue;
      line_ += size_t(std::count(text_.begin() + std::ptrdiff_t(cursor_), text_.begin() + std::ptrdiff_t(after), '\n'));
      cursor_ = after;  // past this key: the next is searched for after it
      return line_;
    }
    return 0;
  }
  // What the parsed document will hold in memory, counted as it is built so that a small file
  // that expands (a million "{}") is refused at the memory limit, not by the kernel. Estimates
  // for libstdc++: any value 16 B, doubled for a vector's growth (32 B); an object member adds a
  // map node (32 B) with its key (32 B) and the allocator's 16 B; a container's own block 64 B;
  // text beyond the short-string buffer its own block.
  static constexpr double kValueBytes = 32.0, kMemberBytes = 80.0, kContainerBytes = 64.0;
  static double heapTextBytes(const std::string& t) { return t.size() > 15 ? double(t.size()) + 17.0 : 0.0; }
  void account(double bytes) {
    domBytes_ += bytes;
    if (domBytes_ > double(memoryLimitBytes()))
      throw InputError(name_, "", formatBytes(domBytes_) + " once parsed",
                       "a document that fits the memory limit " + formatBytes(double(memoryLimitBytes())) +
                           " (--max-memory)");
  }

  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  std::vector<std::unordered_map<std::string, size_t>> keys_;  // per open object: key -> line
  size_t open_ = 0;  // objects open (the first open_ maps of keys_ are theirs)
  double domBytes_ = 0.0;
  size_t cursor_ = 0, line_ = 1;
  const std::string& text_;
  const std::string& name_;
  const bool locateKeys_;
  int depth_ = 0;
};

Json parseJsonPass(const std::string& text, const std::string& name, bool locateKeys) {
  Json root;
  CheckedSax sax(root, text, name, locateKeys);
  if (!Json::sax_parse(text, &sax, nlohmann::detail::input_format_t::json, /*strict=*/true,
                       /*ignore_comments=*/false))
    throw InputError(name, "", "malformed JSON", "valid JSON");
  return root;
}

}  // namespace

Json parseJsonText(const std::string& text, const std::string& name) {
  try {
    return parseJsonPass(text, name, false);
  } catch (const DuplicateKeySeen&) {
    return parseJsonPass(text, name, true);  // throws, naming both lines
  }
}

Json readJsonFile(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "", "a readable JSON file (cannot open it)");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return parseJsonText(text, path);
}

// Appends `j` compactly, stopping once `out` is longer than `limit`: each level adds a
// character before descending, so the recursion is at most `limit` deep.
static void appendValueText(const Json& j, std::string& out, size_t limit) {
  if (out.size() > limit) return;
  if (j.is_array() || j.is_object()) {
    out += j.is_array() ? '[' : '{';
    bool first = true;
    for (auto it = j.begin(); it != j.end() && out.size() <= limit; ++it, first = false) {
      if (!first) out += ',';
      if (j.is_object()) out += jsonText(Json(it.key())) + ':';
      appendValueText(it.value(), out, limit);
    }
    out += j.is_array() ? ']' : '}';
  } else {
    out += jsonText(j);
  }
}

std::string jsonText(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }

std::string jsonValueText(const Json& j) {
  std::string s;
  appendValueText(j, s, 60);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

JsonObject::JsonObject(const Json& j, std::string file, std::string path)
    : j_(j), file_(std::move(file)), path_(std::move(path)) {
  if (!j_.is_object()) throw InputError(file_, path_.empty() ? "(top level)" : path_, jsonValueText(j_), "a JSON object");
}

std::string JsonObject::keyPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonObject::fail(const std::string& key, const std::string& value,
                      const std::string& expected) const {
  throw InputError(file_, keyPath(key), value, expected);
}

bool JsonObject::has(const std::string& key) const {
  asked_.insert(key);
  if (!j_.contains(key)) return false;
  used_.insert(key);
  return true;
}

std::string JsonObject::closestKey(const std::string& key) const {
  std::vector<std::string> present;
  for (auto it = j_.begin(); it != j_.end(); ++it) present.push_back(it.key());
  return closestName(key, present);
}

const Json& JsonObject::get(const std::string& key) const {
  asked_.insert(key);
  auto it = j_.find(key);
  if (it == j_.end()) {
    std::string near = closestKey(key);
    fail(key, "(missing)",
         near.empty() ? "this required key" : "this required key (did you mean it instead of '" + near + "'?)");
  }
  used_.insert(key);
  return *it;
}

const Json& JsonObject::raw(const std::string& key) const { return get(key); }

// Every number a file gives must lie in its key's range (core/settings_table.h); an array's
// element is reported with the whole array, as the file has it.
void JsonObject::checkRange(const std::string& key, double v, const Json* array) const {
  const SettingInfo* info = findSetting(key, kFileScope);
  if (!info || std::isnan(info->lo) || (v >= info->lo && v <= info->hi)) return;
  if (!array) checkSettingRange(*info, v, file_, keyPath(key));
  fail(key, jsonValueText(*array), rangeText(*info) + " for each element");
}

double JsonObject::number(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) fail(key, jsonValueText(v), "a finite number");
  checkRange(key, v.get<double>());
  return v.get<double>();
}
double JsonObject::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}
double JsonObject::positive(const std::string& key) const {
  double v = number(key);
  if (!(v > 0.0)) fail(key, jsonValueText(j_.at(key)), "a number > 0");
  return v;
}
double JsonObject::positive(const std::string& key, double fallback) const {
  return has(key) ? positive(key) : fallback;
}
// The whole number `v` holds exactly (an integer, or a float with no fraction part), if it is
// one within [lo, hi]; read from the number's own type, so nothing is rounded or wrapped.
static std::optional<int> wholeNumber(const Json& v, int lo, int hi) {
  int64_t i = 0;
  if (v.is_number_unsigned()) {
    const uint64_t u = v.get<uint64_t>();
    if (u > uint64_t(std::numeric_limits<int64_t>::max())) return std::nullopt;
    i = int64_t(u);
  } else if (v.is_number_integer()) {
    i = v.get<int64_t>();
  } else if (v.is_number_float()) {
    const double d = v.get<double>();
    if (!(d >= double(lo) && d <= double(hi)) || d != std::trunc(d)) return std::nullopt;  // NaN fails
    return int(d);
  } else {
    return std::nullopt;
  }
  if (i < lo || i > hi) return std::nullopt;
  return int(i);
}

// "a whole number >= 1", "whole numbers in [0, 1000]", ...
static std::string wholeNumbersText(int lo, int hi, bool plural) {
  std::string s = plural ? "whole numbers" : "a whole number";
  constexpr int kMin = std::numeric_limits<int>::min(), kMax = std::numeric_limits<int>::max();
  if (lo == kMin && hi == kMax) return s + " in [" + std::to_string(kMin) + ", " + std::to_string(kMax) + "]";
  if (hi == kMax) return s + " >= " + std::to_string(lo);
  if (lo == kMin) return s + " <= " + std::to_string(hi);
  return s + " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

int JsonObject::integer(const std::string& key) const {
  return integer(key, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
}
int JsonObject::integer(const std::string& key, int fallback) const {
  return has(key) ? integer(key) : fallback;
}
int JsonObject::integer(const std::string& key, int lo, int hi) const {
  const Json& v = get(key);
  const std::optional<int> n = wholeNumber(v, lo, hi);
  if (!n) fail(key, jsonValueText(v), wholeNumbersText(lo, hi, false));
  checkRange(key, *n);
  return *n;
}
std::vector<int> JsonObject::integers(const std::string& key, int lo, int hi) const {
  const Json& v = get(key);
  if (!v.is_array()) fail(key, jsonValueText(v), "an array of " + wholeNumbersText(lo, hi, true));
  std::vector<int> r;
  for (const auto& e : v) {
    const std::optional<int> n = wholeNumber(e, lo, hi);
    if (!n) fail(key, jsonValueText(v), "an array of " + wholeNumbersText(lo, hi, true));
    checkRange(key, *n, &v);
    r.push_back(*n);
  }
  return r;
}
bool JsonObject::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const Json& v = get(key);
  if (!v.is_boolean()) fail(key, jsonValueText(v), "true or false");
  return v.get<bool>();
}
std::string JsonObject::string(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_string()) fail(key, jsonValueText(v), "a string");
  return v.get<std::string>();
}
std::string JsonObject::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}
std::string JsonObject::choice(const std::string& key, const std::vector<std::string>& allowed) const {
  std::string s = string(key);
  for (const auto& a : allowed)
    if (a == s) return s;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  fail(key, "\"" + messageText(s) + "\"", "one of: " + list);
}
std::string JsonObject::choice(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) const {
  return has(key) ? choice(key, allowed) : fallback;
}
Vec3d JsonObject::vec3(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_array() || v.size() != 3) fail(key, jsonValueText(v), "an array of 3 numbers");
  Vec3d r;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      fail(key, jsonValueText(v), "an array of 3 finite numbers");
    r[i] = v[i].get<double>();
    checkRange(key, r[i], &v);
  }
  return r;
}
Vec3d JsonObject::vec3(const std::string& key, const Vec3d& fallback) const {
  return has(key) ? vec3(key) : fallback;
}
std::vector<double> JsonObject::numbers(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_array()) fail(key, jsonValueText(v), "an array of numbers");
  std::vector<double> r;
  for (const auto& e : v) {
    if (!e.is_number() || !std::isfinite(e.get<double>())) fail(key, jsonValueText(v), "an array of finite numbers");
    checkRange(key, e.get<double>(), &v);
    r.push_back(e.get<double>());
  }
  return r;
}
JsonObject JsonObject::object(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_object()) fail(key, jsonValueText(v), "a JSON object");
  return JsonObject(v, file_, keyPath(key));
}
std::vector<JsonObject> JsonObject::objects(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_array()) fail(key, jsonValueText(v), "an array of objects");
  std::vector<JsonObject> r;
  for (size_t i = 0; i < v.size(); ++i) {
    std::string p = keyPath(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) throw InputError(file_, p, jsonValueText(v[i]), "a JSON object");
    r.emplace_back(v[i], file_, p);
  }
  return r;
}
std::string JsonObject::path(const std::string& key) const {
  std::filesystem::path p = string(key);
  if (p.is_relative() && !file_.empty()) p = std::filesystem::path(file_).parent_path() / p;
  return p.lexically_normal().string();
}

void JsonObject::rejectUnknown() const {
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (used_.count(it.key())) continue;
    if (!it.key().empty() && it.key()[0] == '_') continue;  // "_comment", "_source": notes
    std::string known;
    for (const auto& k : asked_) known += (known.empty() ? "" : ", ") + k;
    throw InputError(file_, keyPath(messageText(it.key())), jsonValueText(it.value()),
                     "a known key (unknown key; known keys: " + (known.empty() ? "none" : known) +
                         ")");
  }
}

}  // namespace inim
