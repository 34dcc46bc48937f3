// The .cube reader and writer (declared in lut_io.h).
#include <cmath>
#include <sstream>
#include <string>

#include "calibration/lut_io.h"
#include "calibration/lut_text.h"
#include "core/error.h"
#include "core/output_file.h"

namespace inim {

void writeCube(const std::string& path, const Lut3d& lut, const std::string& title) {
  std::string text;
  text.reserve(lut.values().size() * 40 + 200);
  std::string cleanTitle = title;
  for (char& c : cleanTitle)
    if (c == '"' || c == '\n' || c == '\r') c = ' ';
  text += "TITLE \"" + cleanTitle + "\"\n";
  text += "LUT_3D_SIZE " + std::to_string(lut.size()) + "\n";
  text += "DOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n";
  for (const Vec3d& v : lut.values()) text += tripleText(v) + "\n";  // red fastest
  writeTextFile(path, text);
}

namespace {

// What a .cube file has declared so far while it is read.
struct CubeReader {
  std::string path;
  int size = 0;
  std::vector<Vec3d> values;
  int lineNumber = 0;

  std::string where() const { return "line " + std::to_string(lineNumber); }

  Vec3d triple(const std::vector<std::string_view>& tokens, size_t first, const std::string& key,
               const std::string& line) const {
    if (tokens.size() != first + 3) throw InputError(path, key, line, "three numbers");
    Vec3d v;
    for (int c = 0; c < 3; ++c) {
      const std::string_view token = tokens[first + c];
      if (!parseNumber(token, v[c])) throw InputError(path, key, std::string(token), "a number");
      if (!std::isfinite(v[c])) throw InputError(path, key, std::string(token), "a finite number");
    }
    return v;
  }

  void keyword(const std::vector<std::string_view>& tokens, const std::string& line) {
    const std::string key(tokens[0]);
    if (!values.empty()) throw InputError(path, where(), line, "keywords before the table, none after it");
    if (key == "TITLE") return;
    if (key == "LUT_1D_SIZE") throw InputError(path, key, line, "a 3D LUT (LUT_3D_SIZE), not a 1D LUT");
    if (key == "LUT_3D_SIZE") return readSize(tokens, line);
    if (key == "DOMAIN_MIN" || key == "DOMAIN_MAX") {
      const Vec3d bound = triple(tokens, 1, key, line);
      const double wanted = key == "DOMAIN_MIN" ? 0.0 : 1.0;
      if (bound != Vec3d(wanted))
        throw InputError(path, key, tripleText(bound),
                         key == "DOMAIN_MIN" ? "0 0 0 (the domain [0,1] of every axis)" : "1 1 1 (the domain [0,1] of every axis)");
      return;
    }
    throw InputError(path, where(), key, "TITLE, LUT_3D_SIZE, DOMAIN_MIN, DOMAIN_MAX or a line of three numbers");
  }

  void readSize(const std::vector<std::string_view>& tokens, const std::string& line) {
    double n = 0.0;
    if (tokens.size() != 2 || !parseNumber(tokens[1], n) || n != std::floor(n) || n < 2 || n > 256)
      throw InputError(path, "LUT_3D_SIZE", line, "one whole number of nodes per axis, 2 to 256");
    if (size != 0) throw InputError(path, "LUT_3D_SIZE", line, "a single LUT_3D_SIZE line");
    size = int(n);
  }

  void line(const std::string& raw) {
    ++lineNumber;
    const std::vector<std::string_view> tokens = splitWhitespace(raw);
    if (tokens.empty() || tokens[0][0] == '#') return;
    const char first = tokens[0][0];
    double number = 0.0;  // "nan" and "inf" are numbers (refused later as non-finite), not keywords
    if (((first >= 'A' && first <= 'Z') || (first >= 'a' && first <= 'z')) && !parseNumber(tokens[0], number))
      return keyword(tokens, raw);
    if (size == 0) throw InputError(path, "LUT_3D_SIZE", "missing before " + where(), "LUT_3D_SIZE N before the table");
    values.push_back(triple(tokens, 0, where(), raw));
  }
};

}  // namespace

Lut3d readCube(const std::string& path) {
  std::istringstream text(readTextFile(path, ".cube LUT"));
  CubeReader reader;
  reader.path = path;
  for (std::string line; std::getline(text, line);) reader.line(line);
  if (reader.size == 0) throw InputError(path, "LUT_3D_SIZE", "missing", "LUT_3D_SIZE N");
  const size_t expected = size_t(reader.size) * reader.size * reader.size;
  if (reader.values.size() != expected)
    throw InputError(path, "LUT_3D_SIZE", std::to_string(reader.size),
                     std::to_string(expected) + " table lines (found " + std::to_string(reader.values.size()) + ")");
  Lut3d lut(reader.size);
  for (size_t i = 0; i < expected; ++i)
    lut.set(int(i % reader.size), int(i / reader.size % reader.size), int(i / (size_t(reader.size) * reader.size)),
            reader.values[i]);
  return lut;
}

}  // namespace inim
