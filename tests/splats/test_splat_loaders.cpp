// Splat loaders: the real files of tests/data/splats and scenes/splats, generated files for
// each layout feature (normals, comments, types, order) and each class of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "fixtures.h"
#include "splat_test_files.h"
#include "splats/ply_reader.h"
#include "splats/splat_loaders.h"

namespace inim {
namespace {

using namespace splat_test;
using fixtures::expectInputError;
using fixtures::scratchFile;

std::string dataFile(const std::string& rel) { return std::string(INIM_SOURCE_DATA_DIR) + "/" + rel; }

float sigmoid(double x) { return float(1.0 / (1.0 + std::exp(-x))); }

// The same three splats from .ply (float32, SH 3) and .splat (8-bit colour, opacity and
// quaternion). The .splat format's quantisation bounds the differences: colour
// 0.5 + C0 f_dc and opacity are stored as a byte of 255 steps (1/255 with truncation, half
// that when rounded); quaternion components as (q + 1) * 128 in a byte (1/128 per component
// before renormalising, so 2/128 after); positions and scales are float32 in both (scales
// after exp, so 1e-6 relative).
TEST(SplatLoaders, ThreeSplatsFromPlyAndSplatAgree) {
  const Gaussians ply = loadGaussians(dataFile("tests/data/splats/metalsplatter-3pts.ply"));
  const Gaussians spl = loadGaussians(dataFile("tests/data/splats/metalsplatter-3pts.splat"));
  ASSERT_EQ(ply.size(), 3u);
  ASSERT_EQ(spl.size(), 3u);
  EXPECT_EQ(ply.shDegree, 3);
  EXPECT_EQ(spl.shDegree, 0);
  for (size_t i = 0; i < 3; ++i) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(ply.position[i][a], spl.position[i][a], 1e-6f * (1.0f + std::fabs(ply.position[i][a])));
      EXPECT_NEAR(ply.scale[i][a], spl.scale[i][a], 1e-6f * ply.scale[i][a] + 1e-9f);
      const float cPly = 0.5f + kShC0 * ply.shCoeff(i, 0)[a], cSpl = 0.5f + kShC0 * spl.shCoeff(i, 0)[a];
      EXPECT_NEAR(std::clamp(cPly, 0.0f, 1.0f), cSpl, 1.0f / 255.0f + 1e-6f) << "splat " << i << " channel " << a;
    }
    EXPECT_NEAR(ply.opacity[i], spl.opacity[i], 1.0f / 255.0f + 1e-6f);
    const float sign = glm::dot(ply.rotation[i], spl.rotation[i]) < 0.0f ? -1.0f : 1.0f;
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(ply.rotation[i][c], sign * spl.rotation[i][c], 2.0f / 128.0f);
  }
}

// 100 SH-3 splats followed by 14,029 bytes the header does not describe: the loader reads the
// 100 and ignores the rest. Values are checked against the raw float32 rows read here.
TEST(SplatLoaders, InriaSh3HundredSplatsDespiteTrailingBytes) {
  const std::string path = dataFile("tests/data/splats/cvlab_pc_short.ply");
  const Gaussians g = loadGaussians(path);
  ASSERT_EQ(g.size(), 100u);
  EXPECT_EQ(g.shDegree, 3);
  ASSERT_EQ(g.sh.size(), 100u * 16u * 3u);
  const std::string bytes = fixtures::readBytes(path);
  const size_t dataStart = bytes.find("end_header\n") + 11;
  ASSERT_EQ(bytes.size() - dataStart, 100u * 62u * 4u + 14029u);
  auto raw = [&](size_t i, int p) {
    float v;
    std::memcpy(&v, bytes.data() + dataStart + (i * 62 + size_t(p)) * 4, 4);
    return v;
  };
  for (size_t i : {size_t(0), size_t(57), size_t(99)}) {
    EXPECT_EQ(g.position[i].y, raw(i, 1));
    EXPECT_EQ(g.shCoeff(i, 0).z, raw(i, 8));             // f_dc_2
    EXPECT_EQ(g.shCoeff(i, 1).x, raw(i, 9 + 0));         // f_rest_0: red, coefficient 1
    EXPECT_EQ(g.shCoeff(i, 1).y, raw(i, 9 + 15));        // f_rest_15: green, coefficient 1
    EXPECT_EQ(g.shCoeff(i, 15).z, raw(i, 9 + 44));       // f_rest_44: blue, coefficient 15
    EXPECT_NEAR(g.opacity[i], sigmoid(raw(i, 54)), 1e-6f);
    EXPECT_NEAR(g.scale[i].z, std::exp(raw(i, 57)), 1e-6f * std::exp(raw(i, 57)));
    const glm::vec4 q(raw(i, 58), raw(i, 59), raw(i, 60), raw(i, 61));
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(g.rotation[i][c], q[c] / glm::length(q), 1e-6f);
  }
}

// The PlayCanvas example guitar: 90,854 splats in 355 chunks of 256, SH 0. Every value finite
// and plausible: positions inside their chunk's box, log-scales inside the chunk's range,
// unit quaternions, opacity in [0, 1], colour inside the chunk's colour range.
TEST(SplatLoaders, GuitarCompressedPly) {
  const std::string path = dataFile("scenes/splats/guitar.compressed.ply");
  const PlyFile ply = PlyFile::read(path);
  const PlyElement& ch = ply.element("chunk");
  EXPECT_EQ(ch.count, 355u);
  const Gaussians g = loadGaussians(path);
  ASSERT_EQ(g.size(), 90854u);
  EXPECT_EQ(g.shDegree, 0);
  for (size_t i = 0; i < g.size(); ++i) {
    const size_t c = i / 256;
    for (int a = 0; a < 3; ++a) {
      const char* lo[] = {"min_x", "min_y", "min_z"};
      const char* hi[] = {"max_x", "max_y", "max_z"};
      const char* slo[] = {"min_scale_x", "min_scale_y", "min_scale_z"};
      const char* shi[] = {"max_scale_x", "max_scale_y", "max_scale_z"};
      const char* clo[] = {"min_r", "min_g", "min_b"};
      const char* chi[] = {"max_r", "max_g", "max_b"};
      const float eps = 1e-5f;
      ASSERT_GE(g.position[i][a], ply.value(ch, c, ch.find(lo[a])) - eps);
      ASSERT_LE(g.position[i][a], ply.value(ch, c, ch.find(hi[a])) + eps);
      ASSERT_GE(std::log(g.scale[i][a]), ply.value(ch, c, ch.find(slo[a])) - 1e-4);
      ASSERT_LE(std::log(g.scale[i][a]), ply.value(ch, c, ch.find(shi[a])) + 1e-4);
      const float colour = 0.5f + kShC0 * g.shCoeff(i, 0)[a];
      ASSERT_GE(colour, ply.value(ch, c, ch.find(clo[a])) - 1e-5);
      ASSERT_LE(colour, ply.value(ch, c, ch.find(chi[a])) + 1e-5);
    }
    ASSERT_NEAR(glm::length(g.rotation[i]), 1.0f, 1e-5f);
    ASSERT_GE(g.opacity[i], 0.0f);
    ASSERT_LE(g.opacity[i], 1.0f);
  }
}

// Nerfstudio-style: no normals, properties in another order, header comments, double type.
TEST(SplatLoaders, InriaPropertiesByNameAnyOrderAndType) {
  std::vector<std::string> names = inriaNames(9, false);
  std::reverse(names.begin(), names.end());
  PlyOptions o;
  o.type = "double";
  o.comments = "comment Generated by a trainer\ncomment second line\n";
  const std::string path = scratchFile("splats_double.ply", makePly(names, inriaRows(names, 4), o));
  const Gaussians g = loadGaussians(path);
  ASSERT_EQ(g.size(), 4u);
  EXPECT_EQ(g.shDegree, 1);
  for (int i = 0; i < 4; ++i) {
    EXPECT_FLOAT_EQ(g.position[size_t(i)].x, float(rawValue("x", i)));
    EXPECT_FLOAT_EQ(g.scale[size_t(i)].y, float(std::exp(rawValue("scale_1", i))));
    EXPECT_FLOAT_EQ(g.opacity[size_t(i)], sigmoid(rawValue("opacity", i)));
    // f_rest channel-major with 3 coefficients per channel: f_rest_4 = green, coefficient 2.
    EXPECT_FLOAT_EQ(g.shCoeff(size_t(i), 2).y, float(rawValue("f_rest_4", i)));
    EXPECT_FLOAT_EQ(g.shCoeff(size_t(i), 3).z, float(rawValue("f_rest_8", i)));
  }
}

TEST(SplatLoaders, InriaUcharPropertiesReadAsDeclared) {
  const std::vector<std::string> names = inriaNames(0);
  std::vector<std::vector<double>> rows = {std::vector<double>(names.size(), 3.0)};
  PlyOptions o;
  o.type = "uchar";
  const Gaussians g = loadGaussians(scratchFile("splats_uchar.ply", makePly(names, rows, o)));
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g.shDegree, 0);
  EXPECT_FLOAT_EQ(g.position[0].z, 3.0f);
  EXPECT_FLOAT_EQ(g.scale[0].x, std::exp(3.0f));
  EXPECT_FLOAT_EQ(g.rotation[0].x, 0.5f);  // (3, 3, 3, 3) normalised
}

// A compressed PLY built here: one chunk, packed values chosen so the decoded ones are known.
TEST(SplatLoaders, CompressedPlyDecodesPackedFields) {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement chunk 1\n"
      "property float min_x\nproperty float min_y\nproperty float min_z\nproperty float max_x\n"
      "property float max_y\nproperty float max_z\nproperty float min_scale_x\nproperty float min_scale_y\n"
      "property float min_scale_z\nproperty float max_scale_x\nproperty float max_scale_y\n"
      "property float max_scale_z\nproperty float min_r\nproperty float min_g\nproperty float min_b\n"
      "property float max_r\nproperty float max_g\nproperty float max_b\n"
      "element vertex 2\nproperty uint packed_position\nproperty uint packed_rotation\n"
      "property uint packed_scale\nproperty uint packed_color\n"
      "element sh 2\n";
  for (int k = 0; k < 9; ++k) s += "property uchar f_rest_" + std::to_string(k) + "\n";
  s += "end_header\n";
  for (double v : {-1.0, -2.0, -3.0, 1.0, 2.0, 3.0, -5.0, -5.0, -5.0, -1.0, -1.0, -1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0})
    put(s, "float", v);
  // Quaternion (w, x, y, z) = (0.1, 0.2, 0.9, 0.3) / |.|: the largest is y (index 2); the others
  // (w, x, z) follow in order, each as q / sqrt(2) + 0.5 in 10 bits (|q| < 1/sqrt(2) for them).
  const glm::dvec4 q = glm::normalize(glm::dvec4(0.1, 0.2, 0.9, 0.3));
  auto ten = [](double c) { return uint32_t(std::lround((c / std::sqrt(2.0) + 0.5) * 1023.0)); };
  const uint32_t rot = (2u << 30) | (ten(q[0]) << 20) | (ten(q[1]) << 10) | ten(q[3]);
  const uint32_t pos0 = (2047u << 21) | (0u << 11) | 0u;      // x = max, y = min, z = min
  const uint32_t scale0 = (0u << 21) | (1023u << 11) | 2047u;  // x = min, y = max, z = max
  const uint32_t colour0 = (255u << 24) | (0u << 16) | (0u << 8) | 255u;  // red, alpha 1
  for (uint32_t v : {pos0, rot, scale0, colour0}) put(s, "uint", v);
  for (uint32_t v : {0u, (2u << 30) | (511u << 20) | (511u << 10) | 511u, 0u, 0x80808080u}) put(s, "uint", v);
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 9; ++k) put(s, "uchar", k == 4 ? 255.0 : 0.0);  // f_rest_4: green, coefficient 2
  const Gaussians g = loadGaussians(scratchFile("splats_compressed.ply", s));
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g.shDegree, 1);
  EXPECT_NEAR(g.position[0].x, 1.0f, 1e-6f);
  EXPECT_NEAR(g.position[0].y, -2.0f, 1e-6f);
  EXPECT_NEAR(g.position[0].z, -3.0f, 1e-6f);
  EXPECT_NEAR(g.scale[0].x, std::exp(-5.0f), 1e-6f);
  EXPECT_NEAR(g.scale[0].y, std::exp(-1.0f), 1e-6f);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(g.rotation[0][c], float(q[c]), 2e-3f) << c;
  EXPECT_NEAR(0.5f + kShC0 * g.shCoeff(0, 0).x, 1.0f, 1e-6f);
  EXPECT_NEAR(0.5f + kShC0 * g.shCoeff(0, 0).y, 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(g.opacity[0], 1.0f);
  EXPECT_NEAR(g.opacity[1], 128.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(g.shCoeff(1, 2).y, 4.0f, 1e-6f);
  EXPECT_NEAR(g.shCoeff(1, 2).x, -4.0f, 1e-6f);
  EXPECT_NEAR(g.shCoeff(1, 1).y, -4.0f, 1e-6f);
}

// ---- Bad input: InputError naming the file, element and property --------------------------

std::string goodPly(const PlyOptions& o = {}, int n = 3) {
  const std::vector<std::string> names = inriaNames(9);
  return makePly(names, inriaRows(names, n), o);
}

TEST(SplatLoadersBadInput, BigEndianAndUnknownFormatsAreRejected) {
  for (const char* fmt : {"binary_big_endian 1.0", "binary_middle_endian 1.0"}) {
    PlyOptions o;
    o.format = fmt;
    const std::string path = scratchFile("splats_fmt.ply", goodPly(o));
    const InputError e = expectInputError([&] { loadGaussians(path); });
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.key(), "format");
    EXPECT_NE(e.value().find(fmt), std::string::npos);
  }
}

// ASCII rows: the header of makePly with the values written as text.
std::string asciiPly(const std::vector<std::string>& names, const std::vector<std::vector<std::string>>& rows, long declared = -1) {
  std::string s = "ply\nformat ascii 1.0\ncomment written by hand\nelement vertex " +
                  std::to_string(declared >= 0 ? size_t(declared) : rows.size()) + "\n";
  for (const std::string& n : names) s += "property float " + n + "\n";
  s += "end_header\n";
  for (const auto& r : rows) {
    for (const std::string& v : r) s += v + " ";
    s += "\n";
  }
  return s;
}

std::vector<std::vector<std::string>> asText(const std::vector<std::vector<double>>& rows) {
  std::vector<std::vector<std::string>> out;
  for (const auto& r : rows) {
    out.emplace_back();
    for (double v : r) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.9g", double(float(v)));  // the binary file's float, exactly
      out.back().push_back(buf);
    }
  }
  return out;
}

TEST(SplatLoaders, AsciiPlyGivesTheBinaryFilesGaussians) {
  const std::vector<std::string> names = inriaNames(24);
  const auto rows = inriaRows(names, 5);
  const Gaussians bin = loadGaussians(scratchFile("splats_bin.ply", makePly(names, rows)));
  const Gaussians asc = loadGaussians(scratchFile("splats_ascii.ply", asciiPly(names, asText(rows))));
  ASSERT_EQ(asc.size(), 5u);
  EXPECT_EQ(asc.shDegree, 2);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(asc.position[i], bin.position[i]);
    EXPECT_EQ(asc.rotation[i], bin.rotation[i]);
    EXPECT_EQ(asc.scale[i], bin.scale[i]);
    EXPECT_EQ(asc.opacity[i], bin.opacity[i]);
  }
  EXPECT_EQ(asc.sh, bin.sh);
}

TEST(SplatLoadersBadInput, AsciiMalformedNumberOrTooFewRows) {
  const std::vector<std::string> names = inriaNames(0);
  auto rows = asText(inriaRows(names, 3));
  rows[2][1] = "1.5e";  // y of splat 2
  const std::string bad = scratchFile("splats_ascii_bad.ply", asciiPly(names, rows));
  InputError e = expectInputError([&] { loadGaussians(bad); });
  EXPECT_EQ(e.key(), "vertex.y");
  EXPECT_NE(e.value().find("1.5e"), std::string::npos);
  const std::string shortFile = scratchFile("splats_ascii_short.ply", asciiPly(names, asText(inriaRows(names, 3)), 4));
  e = expectInputError([&] { loadGaussians(shortFile); });
  EXPECT_EQ(e.key(), "vertex");
  const std::string huge = scratchFile("splats_ascii_huge.ply", asciiPly(names, asText(inriaRows(names, 1)), 3000000000000L));
  EXPECT_EQ(expectInputError([&] { loadGaussians(huge); }).key(), "vertex");
}

TEST(SplatLoadersBadInput, TruncatedAndImpossibleCounts) {
  const std::string whole = goodPly();
  const std::string cut = scratchFile("splats_cut.ply", whole.substr(0, whole.size() - 5));
  InputError e = expectInputError([&] { loadGaussians(cut); });
  EXPECT_EQ(e.key(), "vertex");
  EXPECT_EQ(e.file(), cut);
  // A count no file this size can hold (and no machine could allocate for): refused first.
  PlyOptions o;
  o.declaredCount = 4000000000000L;
  const std::string huge = scratchFile("splats_huge.ply", goodPly(o));
  e = expectInputError([&] { loadGaussians(huge); });
  EXPECT_EQ(e.key(), "vertex");
  EXPECT_NE(e.value().find("4000000000000"), std::string::npos);
  const std::string noEnd = scratchFile("splats_noend.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1\n");
  EXPECT_EQ(expectInputError([&] { loadGaussians(noEnd); }).key(), "header");
  const std::string splat = scratchFile("splats_cut.splat", std::string(33, '\0'));
  EXPECT_EQ(expectInputError([&] { loadGaussians(splat); }).key(), "splat");
}

TEST(SplatLoadersBadInput, MissingPropertyNamesIt) {
  std::vector<std::string> names = inriaNames(0);
  names.erase(names.begin() + indexOf(names, "opacity"));
  const std::string path = scratchFile("splats_noopacity.ply", makePly(names, inriaRows(names, 2)));
  const InputError e = expectInputError([&] { loadGaussians(path); });
  EXPECT_EQ(e.key(), "vertex.opacity");
  EXPECT_EQ(e.file(), path);
  // 10 f_rest: no SH degree has that many.
  std::vector<std::string> odd = inriaNames(10);
  const std::string oddPath = scratchFile("splats_oddrest.ply", makePly(odd, inriaRows(odd, 1)));
  EXPECT_EQ(expectInputError([&] { loadGaussians(oddPath); }).key(), "vertex.f_rest_*");
}

// One bad raw value at splat 1, property `name`: the error names vertex.<name> (or the
// quaternion) and the splat.
InputError badValue(const std::string& name, double value, const std::string& file) {
  const std::vector<std::string> names = inriaNames(0);
  auto rows = inriaRows(names, 3);
  if (name == "rot")
    for (int c = 0; c < 4; ++c) rows[1][size_t(indexOf(names, "rot_" + std::to_string(c)))] = 0.0;
  else
    rows[1][size_t(indexOf(names, name))] = value;
  const std::string path = scratchFile(file, makePly(names, rows));
  InputError e = expectInputError([&] { loadGaussians(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_NE(e.value().find("splat 1"), std::string::npos) << e.what();
  return e;
}

TEST(SplatLoadersBadInput, NonFiniteZeroQuaternionAndScaleOverflow) {
  EXPECT_EQ(badValue("y", std::nan(""), "splats_nan.ply").key(), "vertex.y");
  EXPECT_EQ(badValue("f_dc_1", INFINITY, "splats_inf.ply").key(), "vertex.f_dc_1");
  EXPECT_EQ(badValue("opacity", -INFINITY, "splats_ninf.ply").key(), "vertex.opacity");
  EXPECT_EQ(badValue("rot", 0.0, "splats_zeroq.ply").key(), "vertex.rot_0..3");
  EXPECT_EQ(badValue("scale_2", 100.0, "splats_bigscale.ply").key(), "vertex.scale_2");
  // .splat: 8-bit quaternion (128, 128, 128, 128) is zero.
  std::string rec(32, '\0');
  const float one = 1.0f;
  for (int k = 3; k < 6; ++k) std::memcpy(&rec[size_t(k) * 4], &one, 4);
  for (int k = 28; k < 32; ++k) rec[size_t(k)] = char(128);
  const std::string zeroQ = scratchFile("splats_zeroq.splat", rec);
  EXPECT_EQ(expectInputError([&] { loadGaussians(zeroQ); }).key(), "splat.rot_0..3");
}

TEST(SplatLoadersBadInput, NoSplatsOrWrongExtension) {
  const std::string empty = scratchFile("splats_empty.ply", goodPly({}, 0));
  EXPECT_EQ(expectInputError([&] { loadGaussians(empty); }).key(), "vertex");
  const std::string other = scratchFile("splats.txt", "x");
  EXPECT_EQ(expectInputError([&] { loadGaussians(other); }).key(), "file");
}

}  // namespace
}  // namespace inim
