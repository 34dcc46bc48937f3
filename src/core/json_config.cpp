#include "core/json_config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace inim {

Json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "", "a readable JSON file (cannot open it)");
  try {
    return Json::parse(in, nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::parse_error& e) {
    throw InputError(path, "", "malformed JSON (" + std::string(e.what()) + ")", "valid JSON");
  }
}

std::string jsonValueText(const Json& j) {
  std::string s = j.dump();
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

// Levenshtein distance, for "did you mean" hints on misspelt keys.
static size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string JsonObject::closestKey(const std::string& key) const {
  std::string best;
  size_t bestD = 3;  // up to 2 edits
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    size_t d = editDistance(it.key(), key);
    if (d < bestD) bestD = d, best = it.key();
  }
  return best;
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

double JsonObject::number(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) fail(key, jsonValueText(v), "a finite number");
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
int JsonObject::integer(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_number_integer()) fail(key, jsonValueText(v), "an integer");
  return v.get<int>();
}
int JsonObject::integer(const std::string& key, int fallback) const {
  return has(key) ? integer(key) : fallback;
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
  fail(key, "\"" + s + "\"", "one of: " + list);
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
    throw InputError(file_, keyPath(it.key()), jsonValueText(it.value()),
                     "a known key (unknown key; known keys: " + (known.empty() ? "none" : known) +
                         ")");
  }
}

}  // namespace inim
