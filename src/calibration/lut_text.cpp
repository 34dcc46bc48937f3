#include "calibration/lut_text.h"

#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/input_file.h"
#include "core/error.h"

namespace inim {

std::string exactNumber(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string tripleText(const Vec3d& v) {
  return exactNumber(v.x) + " " + exactNumber(v.y) + " " + exactNumber(v.z);
}

std::vector<std::string_view> splitWhitespace(std::string_view text) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; };
  while (i < text.size()) {
    while (i < text.size() && space(text[i])) ++i;
    const size_t start = i;
    while (i < text.size() && !space(text[i])) ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  return tokens;
}

bool parseNumber(std::string_view token, double& value) {
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

std::string readTextFile(const std::string& path, const std::string& expected) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "", "a readable " + expected);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace inim
