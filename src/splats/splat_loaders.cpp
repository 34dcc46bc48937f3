#include "splats/splat_loaders.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/input_file.h"
#include "core/error.h"
#include "core/file_kinds.h"
#include "core/format.h"
#include "core/ray_check.h"
#include "splats/ply_reader.h"

namespace inim {

namespace {

std::string at(double v, size_t row, const char* what = "splat") {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%g (%s %zu)", v, what, row);
  return buf;
}

// Raw value of property `p` of `e` at `row`, finite or an InputError naming element.property.
double finiteValue(const PlyFile& ply, const PlyElement& e, size_t row, int p) {
  const double v = ply.value(e, row, p);
  if (!std::isfinite(v))
    throw InputError(ply.path(), e.name + "." + e.properties[size_t(p)].name, at(v, row), "a finite number");
  return v;
}

// A position coordinate: finite and within the ray tracer's reach (core/ray_check.h).
double coordinateValue(const PlyFile& ply, const PlyElement& e, size_t row, int p) {
  const double v = finiteValue(ply, e, row, p);
  if (!(std::fabs(v) <= kMaxRayCoordinateMm))
    throw InputError(ply.path(), e.name + "." + e.properties[size_t(p)].name, at(v, row),
                     "a coordinate within +-1e7 (the ray tracer's reach)");
  return v;
}

float activateScale(double logScale, const std::string& file, const std::string& key, size_t row) {
  if (!(std::fabs(logScale) <= kMaxAbsLogScale))
    throw InputError(file, key, at(logScale, row),
                     "a log scale within +-" + std::to_string(int(kMaxAbsLogScale)) + " (exp must stay finite and nonzero)");
  return float(std::exp(logScale));
}

float sigmoid(double x) { return float(1.0 / (1.0 + std::exp(-x))); }

glm::vec4 normalisedQuaternion(glm::dvec4 q, const std::string& file, const std::string& key, size_t row) {
  const double len = glm::length(q);
  if (!(len > 1e-12) || !std::isfinite(len)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g, %g) (splat %zu)", q.x, q.y, q.z, q.w, row);
    throw InputError(file, key, buf, "a nonzero quaternion (w, x, y, z)");
  }
  return glm::vec4(q / len);
}

void requireSplats(const std::string& file, const std::string& key, size_t n) {
  if (n == 0) throw InputError(file, key, "count 0", "at least one splat");
}

// Number of f_rest_k properties, k = 0.. consecutive, in element `e`.
int countRest(const PlyElement& e) {
  int n = 0;
  while (e.find("f_rest_" + std::to_string(n)) >= 0) ++n;
  return n;
}

int shDegreeFromRest(int nRest, const std::string& file, const std::string& key) {
  for (int deg = 0; deg <= 3; ++deg)
    if (nRest == 3 * (splatShCount(deg) - 1)) return deg;
  throw InputError(file, key, std::to_string(nRest) + " coefficients",
                   "0, 9, 24 or 45 f_rest properties (SH degree 0 to 3)");
}

}  // namespace

Gaussians loadInriaPly(const PlyFile& ply) {
  const std::string& file = ply.path();
  const PlyElement& v = ply.element("vertex");
  requireSplats(file, "vertex", v.count);
  const int x = v.require("x", file), y = v.require("y", file), z = v.require("z", file);
  int dc[3], scale[3], rot[4];
  for (int c = 0; c < 3; ++c) dc[c] = v.require("f_dc_" + std::to_string(c), file);
  for (int c = 0; c < 3; ++c) scale[c] = v.require("scale_" + std::to_string(c), file);
  for (int c = 0; c < 4; ++c) rot[c] = v.require("rot_" + std::to_string(c), file);
  const int opacity = v.require("opacity", file);
  const int nRest = countRest(v);
  const int degree = shDegreeFromRest(nRest, file, "vertex.f_rest_*");
  std::vector<int> rest(static_cast<size_t>(nRest));
  for (int k = 0; k < nRest; ++k) rest[size_t(k)] = v.find("f_rest_" + std::to_string(k));

  Gaussians g;
  g.resize(v.count, degree);
  const int perChannel = splatShCount(degree) - 1;
  for (size_t i = 0; i < v.count; ++i) {
    g.position[i] = Vec3(coordinateValue(ply, v, i, x), coordinateValue(ply, v, i, y), coordinateValue(ply, v, i, z));
    for (int c = 0; c < 3; ++c)
      g.scale[i][c] = activateScale(finiteValue(ply, v, i, scale[c]), file, "vertex.scale_" + std::to_string(c), i);
    glm::dvec4 q;
    for (int c = 0; c < 4; ++c) q[c] = finiteValue(ply, v, i, rot[c]);
    g.rotation[i] = normalisedQuaternion(q, file, "vertex.rot_0..3", i);
    g.opacity[i] = sigmoid(finiteValue(ply, v, i, opacity));
    float* sh = &g.sh[i * size_t(g.shPerSplat()) * 3];
    for (int c = 0; c < 3; ++c) sh[c] = float(finiteValue(ply, v, i, dc[c]));
    for (int c = 0; c < 3; ++c)
      for (int k = 1; k <= perChannel; ++k)
        sh[k * 3 + c] = float(finiteValue(ply, v, i, rest[size_t(c * perChannel + k - 1)]));
  }
  return g;
}

namespace {

float unorm(uint32_t v, int bits) { return float(v & ((1u << bits) - 1u)) / float((1u << bits) - 1u); }
Vec3 unpack111011(uint32_t v) { return Vec3(unorm(v >> 21, 11), unorm(v >> 11, 10), unorm(v, 11)); }

// Largest component (w-first index) in the top 2 bits; the others in order, 10 bits each,
// stored as (q + 1/sqrt(2)) * sqrt(2)/2 since a non-largest component is below 1/sqrt(2).
glm::dvec4 unpackRotation(uint32_t v) {
  const double norm = std::sqrt(2.0);
  const double a = (unorm(v >> 20, 10) - 0.5) * norm, b = (unorm(v >> 10, 10) - 0.5) * norm,
               c = (unorm(v, 10) - 0.5) * norm;
  const double m = std::sqrt(std::max(0.0, 1.0 - (a * a + b * b + c * c)));
  switch (v >> 30) {
    case 0: return {m, a, b, c};
    case 1: return {a, m, b, c};
    case 2: return {a, b, m, c};
    default: return {a, b, c, m};
  }
}

struct Chunk {
  Vec3 posLo, posHi, scaleLo, scaleHi, colLo{0.0f}, colHi{1.0f};
};

std::vector<Chunk> readChunks(const PlyFile& ply, const PlyElement& ch) {
  static const char* kPos[] = {"min_x", "min_y", "min_z", "max_x", "max_y", "max_z"};
  static const char* kScale[] = {"min_scale_x", "min_scale_y", "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z"};
  static const char* kCol[] = {"min_r", "min_g", "min_b", "max_r", "max_g", "max_b"};
  int pos[6], scale[6], col[6];
  for (int k = 0; k < 6; ++k) pos[k] = ch.require(kPos[k], ply.path());
  for (int k = 0; k < 6; ++k) scale[k] = ch.require(kScale[k], ply.path());
  const bool hasColour = ch.find("min_r") >= 0;
  if (hasColour)
    for (int k = 0; k < 6; ++k) col[k] = ch.require(kCol[k], ply.path());
  std::vector<Chunk> chunks(ch.count);
  for (size_t i = 0; i < ch.count; ++i) {
    Chunk& c = chunks[i];
    for (int k = 0; k < 3; ++k) {
      c.posLo[k] = float(coordinateValue(ply, ch, i, pos[k]));
      c.posHi[k] = float(coordinateValue(ply, ch, i, pos[k + 3]));
      c.scaleLo[k] = float(finiteValue(ply, ch, i, scale[k]));
      c.scaleHi[k] = float(finiteValue(ply, ch, i, scale[k + 3]));
      for (int s : {scale[k], scale[k + 3]})
        activateScale(ply.value(ch, i, s), ply.path(), "chunk." + ch.properties[size_t(s)].name, i);
      if (hasColour) {
        c.colLo[k] = float(finiteValue(ply, ch, i, col[k]));
        c.colHi[k] = float(finiteValue(ply, ch, i, col[k + 3]));
      }
    }
  }
  return chunks;
}

int requireUint(const PlyElement& e, const std::string& name, const std::string& file) {
  const int p = e.require(name, file);
  if (e.properties[size_t(p)].type != PlyType::UInt32)
    throw InputError(file, e.name + "." + name, "not uint", "a uint (32-bit packed) property");
  return p;
}

// The optional `sh` element: uchar f_rest_* per splat, value = byte * 8/255 - 4.
void readCompressedSh(const PlyFile& ply, Gaussians& g) {
  const PlyElement& s = ply.element("sh");
  if (s.count != g.size())
    throw InputError(ply.path(), "sh", "count " + std::to_string(s.count), "one row per vertex (" + std::to_string(g.size()) + ")");
  const int nRest = countRest(s);
  const int perChannel = nRest / 3;
  std::vector<int> rest(static_cast<size_t>(nRest));
  for (int k = 0; k < nRest; ++k) rest[size_t(k)] = s.find("f_rest_" + std::to_string(k));
  for (size_t i = 0; i < g.size(); ++i) {
    float* sh = &g.sh[i * size_t(g.shPerSplat()) * 3];
    for (int c = 0; c < 3; ++c)
      for (int k = 1; k <= perChannel; ++k)
        sh[k * 3 + c] = float(finiteValue(ply, s, i, rest[size_t(c * perChannel + k - 1)]) * (8.0 / 255.0) - 4.0);
  }
}

}  // namespace

Gaussians loadCompressedPly(const PlyFile& ply) {
  const std::string& file = ply.path();
  const PlyElement& v = ply.element("vertex");
  const PlyElement& ch = ply.element("chunk");
  requireSplats(file, "vertex", v.count);
  const size_t expectedChunks = (v.count + 255) / 256;
  if (ch.count != expectedChunks)
    throw InputError(file, "chunk", "count " + std::to_string(ch.count),
                     std::to_string(expectedChunks) + " chunks (one per 256 of " + std::to_string(v.count) + " vertices)");
  const int pp = requireUint(v, "packed_position", file), pr = requireUint(v, "packed_rotation", file),
            ps = requireUint(v, "packed_scale", file), pc = requireUint(v, "packed_color", file);
  int degree = 0;
  if (ply.has("sh")) degree = shDegreeFromRest(countRest(ply.element("sh")), file, "sh.f_rest_*");
  const std::vector<Chunk> chunks = readChunks(ply, ch);

  Gaussians g;
  g.resize(v.count, degree);
  for (size_t i = 0; i < v.count; ++i) {
    const Chunk& c = chunks[i / 256];
    g.position[i] = glm::mix(c.posLo, c.posHi, unpack111011(ply.valueU32(v, i, pp)));
    const Vec3 logScale = glm::mix(c.scaleLo, c.scaleHi, unpack111011(ply.valueU32(v, i, ps)));
    g.scale[i] = glm::exp(logScale);
    g.rotation[i] = normalisedQuaternion(unpackRotation(ply.valueU32(v, i, pr)), file, "vertex.packed_rotation", i);
    const uint32_t col = ply.valueU32(v, i, pc);
    const Vec3 rgb = glm::mix(c.colLo, c.colHi, Vec3(unorm(col >> 24, 8), unorm(col >> 16, 8), unorm(col >> 8, 8)));
    for (int k = 0; k < 3; ++k) g.sh[i * size_t(g.shPerSplat()) * 3 + size_t(k)] = (rgb[k] - 0.5f) / kShC0;
    g.opacity[i] = unorm(col, 8);
  }
  if (degree > 0) readCompressedSh(ply, g);
  return g;
}

Gaussians loadSplatFile(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, "file", "\"" + path + "\"", "a readable .splat file");
  if (size % 32 != 0)
    throw InputError(path, "splat", std::to_string(size) + " bytes", "a multiple of 32 bytes (one splat per 32 bytes): truncated?");
  const size_t n = size / 32;
  requireSplats(path, "splat", n);
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(size);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw InputError(path, "file", "\"" + path + "\"", "a readable .splat file");
  Gaussians g;
  g.resize(n, 0);
  static const char* kNames[] = {"x", "y", "z", "scale_0", "scale_1", "scale_2"};
  for (size_t i = 0; i < n; ++i) {
    const unsigned char* r = &bytes[i * 32];
    float f[6];
    std::memcpy(f, r, sizeof f);
    for (int k = 0; k < 6; ++k)
      if (!(k < 3 ? std::fabs(f[k]) <= kMaxRayCoordinateMm : f[k] > 0.0f && std::isfinite(f[k])))
        throw InputError(path, std::string("splat.") + kNames[k], at(f[k], i),
                         k < 3 ? "a coordinate within +-1e7 (the ray tracer's reach)" : "a finite scale > 0");
    g.position[i] = Vec3(f[0], f[1], f[2]);
    g.scale[i] = Vec3(f[3], f[4], f[5]);
    for (int c = 0; c < 3; ++c) g.sh[i * 3 + size_t(c)] = (float(r[24 + c]) / 255.0f - 0.5f) / kShC0;
    g.opacity[i] = float(r[27]) / 255.0f;
    const glm::dvec4 q((r[28] - 128.0) / 128.0, (r[29] - 128.0) / 128.0, (r[30] - 128.0) / 128.0, (r[31] - 128.0) / 128.0);
    g.rotation[i] = normalisedQuaternion(q, path, "splat.rot_0..3", i);
  }
  return g;
}

Gaussians loadGaussians(const std::string& path) {
  if (requireFileKind(path, "file", {FileKind::Ply, FileKind::Splat}, "a Gaussian-splat file (.ply or .splat)", path) ==
      FileKind::Splat)
    return loadSplatFile(path);
  const PlyFile ply = PlyFile::read(path);
  if (ply.has("chunk")) return loadCompressedPly(ply);
  return loadInriaPly(ply);
}

}  // namespace inim
