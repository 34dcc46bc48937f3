#include "scene/obj_loader.h"

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "core/input_file.h"
#include "core/error.h"

namespace inim {

namespace {

bool parseFloat(const std::string& tok, float* v) {
  char* end = nullptr;
  *v = std::strtof(tok.c_str(), &end);
  return end && *end == '\0' && end != tok.c_str() && std::isfinite(*v);
}

// OBJ indices are 1-based; negative ones count back from the end.
bool resolve(const std::string& s, size_t count, int* out) {
  if (s.empty()) {
    *out = -1;
    return true;
  }
  long v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || v == 0) return false;
  long idx = v > 0 ? v - 1 : long(count) + v;
  if (idx < 0 || idx >= long(count)) return false;
  *out = int(idx);
  return true;
}

}  // namespace

ObjMesh parseObj(const std::string& text, const std::string& name) {
  std::vector<Vec3> v, vn;
  std::vector<Vec2> vt;
  ObjMesh mesh;
  std::map<std::tuple<int, int, int>, uint32_t> corners;
  bool allN = true, allUV = true;
  std::vector<std::tuple<int, int, int>> cornerKeys;
  std::istringstream in(text);
  std::string line;
  int lineNo = 0;
  auto fail = [&](const std::string& what, const std::string& expected) {
    throw InputError(name, "line " + std::to_string(lineNo), "\"" + what + "\"", expected);
  };
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string kw;
    if (!(ls >> kw) || kw[0] == '#') continue;
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (kw == "v" || kw == "vn") {
      if (tok.size() < 3) fail(line, "3 numbers");
      Vec3 p;
      for (int i = 0; i < 3; ++i)
        if (!parseFloat(tok[i], &p[i])) fail(line, "3 finite numbers");
      (kw == "v" ? v : vn).push_back(p);
    } else if (kw == "vt") {
      if (tok.size() < 2) fail(line, "2 numbers");
      Vec2 p;
      for (int i = 0; i < 2; ++i)
        if (!parseFloat(tok[i], &p[i])) fail(line, "2 finite numbers");
      vt.push_back(p);
    } else if (kw == "f") {
      if (tok.size() < 3) fail(line, "a face with at least 3 corners");
      std::vector<uint32_t> face;
      for (const std::string& t : tok) {
        std::string parts[3];
        int k = 0;
        for (char c : t) {
          if (c == '/') {
            if (++k > 2) fail(line, "corners as v, v/vt, v//vn or v/vt/vn");
          } else {
            parts[k] += c;
          }
        }
        int iv = -1, it = -1, in_ = -1;  // set by resolve, or fail() throws
        if (parts[0].empty() || !resolve(parts[0], v.size(), &iv) ||
            !resolve(parts[1], vt.size(), &it) || !resolve(parts[2], vn.size(), &in_))
          fail(line, "vertex indices that refer to existing v/vt/vn entries");
        if (it < 0) allUV = false;
        if (in_ < 0) allN = false;
        auto key = std::make_tuple(iv, it, in_);
        auto found = corners.find(key);
        uint32_t idx;
        if (found == corners.end()) {
          idx = uint32_t(cornerKeys.size());
          corners.emplace(key, idx);
          cornerKeys.push_back(key);
        } else {
          idx = found->second;
        }
        face.push_back(idx);
      }
      for (size_t i = 1; i + 1 < face.size(); ++i)
        mesh.indices.insert(mesh.indices.end(), {face[0], face[i], face[i + 1]});
    }
    // Anything else (o, g, s, usemtl, mtllib, l, p, ...) carries no geometry we use.
  }
  mesh.P.reserve(cornerKeys.size());
  for (const auto& [iv, it, in_] : cornerKeys) {
    mesh.P.push_back(v[iv]);
    if (allN) mesh.N.push_back(vn[in_]);
    if (allUV) mesh.UV.push_back(vt[it]);
  }
  if (cornerKeys.empty()) allN = allUV = false;
  if (!allN) mesh.N.clear();
  if (!allUV) mesh.UV.clear();
  return mesh;
}

ObjMesh loadObj(const std::string& path) {
  checkInputFile(path);
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "", "", "a readable OBJ file (cannot open it)");
  std::stringstream ss;
  ss << f.rdbuf();
  return parseObj(ss.str(), path);
}

}  // namespace inim
