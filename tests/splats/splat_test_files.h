#pragma once
// Small splat files written by tests: INRIA-layout PLY with chosen properties, types, format
// and row count, and compressed PLY rows, so each loader path and each bad-input class has a
// file of its own.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace splat_test {

// Property names of the INRIA layout with `nRest` f_rest coefficients, normals optional.
inline std::vector<std::string> inriaNames(int nRest, bool normals = true) {
  std::vector<std::string> n = {"x", "y", "z"};
  if (normals) n.insert(n.end(), {"nx", "ny", "nz"});
  for (int c = 0; c < 3; ++c) n.push_back("f_dc_" + std::to_string(c));
  for (int k = 0; k < nRest; ++k) n.push_back("f_rest_" + std::to_string(k));
  n.push_back("opacity");
  for (int c = 0; c < 3; ++c) n.push_back("scale_" + std::to_string(c));
  for (int c = 0; c < 4; ++c) n.push_back("rot_" + std::to_string(c));
  return n;
}

// A plausible raw (pre-activation) value of property `name` for splat `i`.
inline double rawValue(const std::string& name, int i) {
  if (name == "x") return 0.1 * i;
  if (name == "y") return -0.2 * i + 0.05;
  if (name == "z") return 1.0 + 0.01 * i;
  if (name == "opacity") return 0.5 - 0.3 * i;
  if (name.rfind("scale_", 0) == 0) return -3.0 + 0.1 * (name.back() - '0') + 0.05 * i;
  if (name == "rot_0") return 1.0;
  if (name == "rot_1") return 0.2 * i;
  if (name == "rot_2") return -0.1;
  if (name == "rot_3") return 0.3;
  if (name.rfind("f_dc_", 0) == 0) return 0.3 * (name.back() - '0') - 0.2 + 0.01 * i;
  if (name.rfind("f_rest_", 0) == 0) return 0.001 * std::stoi(name.substr(7)) - 0.02 * i;
  return 0.0;
}

struct PlyOptions {
  std::string format = "binary_little_endian 1.0";
  std::string type = "float";  // every property's type
  long declaredCount = -1;     // the header's count (-1: the rows written)
  std::string comments;        // extra header lines
  size_t trailingBytes = 0;
};

inline void put(std::string& out, const std::string& type, double v) {
  auto raw = [&](const auto x) { out.append(reinterpret_cast<const char*>(&x), sizeof x); };
  if (type == "float") raw(float(v));
  else if (type == "double") raw(double(v));
  else if (type == "uchar") raw(uint8_t(v));
  else if (type == "uint") raw(uint32_t(v));
}

inline std::string makePly(const std::vector<std::string>& names, const std::vector<std::vector<double>>& rows,
                           const PlyOptions& o = {}) {
  std::string s = "ply\nformat " + o.format + "\n" + o.comments;
  s += "element vertex " + std::to_string(o.declaredCount >= 0 ? size_t(o.declaredCount) : rows.size()) + "\n";
  for (const std::string& n : names) s += "property " + o.type + " " + n + "\n";
  s += "end_header\n";
  for (const auto& r : rows)
    for (double v : r) put(s, o.type, v);
  s.append(o.trailingBytes, '\x7f');
  return s;
}

// Rows of rawValue for `n` splats.
inline std::vector<std::vector<double>> inriaRows(const std::vector<std::string>& names, int n) {
  std::vector<std::vector<double>> rows(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    for (const std::string& name : names) rows[size_t(i)].push_back(rawValue(name, i));
  return rows;
}

inline int indexOf(const std::vector<std::string>& names, const std::string& n) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == n) return int(i);
  return -1;
}

}  // namespace splat_test
