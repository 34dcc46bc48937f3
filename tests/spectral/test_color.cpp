// Colour-space conversion through OpenColorIO, CIELAB and CIEDE2000.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "spectral/color.h"

namespace inim {
namespace {

const ColorSystem& cs() { return ColorSystem::instance(); }

// lin_rec709 white -> XYZ is the D65 white (0.9505, 1, 1.0888) within 1e-3 (the sRGB
// matrix uses xy = (0.3127, 0.3290): Z = 1.08906).
TEST(Color, WhiteToXYZ) {
  Vec3 xyz = cs().convert(Vec3(1.0f), "lin_rec709", "cie_xyz_d65");
  EXPECT_NEAR(xyz.x, 0.9505f, 1e-3f);
  EXPECT_NEAR(xyz.y, 1.0f, 1e-5f);
  EXPECT_NEAR(xyz.z, 1.0888f, 1e-3f);
  Vec3 m = ColorSystem::rec709ToXYZ() * Vec3(1.0f);
  EXPECT_NEAR(m.x, 0.950456f, 1e-5f);
  EXPECT_NEAR(m.z, 1.089058f, 1e-5f);
}

// sRGB encoding of linear 0.5 is 1.055 * 0.5^(1/2.4) - 0.055 = 0.7353569 (1e-4).
TEST(Color, SrgbEncoding) {
  Vec3 s = cs().convert(Vec3(0.5f), "lin_rec709", "srgb");
  EXPECT_NEAR(s.x, 0.7353569f, 1e-4f);
  EXPECT_NEAR(s.z, 0.7353569f, 1e-4f);
  EXPECT_NEAR(srgbEncode(0.5f), 0.7353569f, 1e-6f);
  // Linear toe: 0.002 -> 12.92 * 0.002.
  EXPECT_NEAR(cs().convert(Vec3(0.002f), "lin_rec709", "srgb").y, 0.02584f, 1e-4f);
  Vec3 back = cs().convert(s, "srgb", "lin_rec709");
  EXPECT_NEAR(back.x, 0.5f, 1e-5f);
  for (float v : {0.0f, 0.001f, 0.04f, 0.2f, 0.9f, 1.0f})
    EXPECT_NEAR(srgbDecode(srgbEncode(v)), v, 1e-6f);
}

// Round trips through the other spaces come back within 1e-5.
TEST(Color, RoundTrips) {
  for (const char* space : {"acescg", "display_p3", "display_p3_encoded", "cie_xyz_d65", "srgb"}) {
    for (Vec3 v : {Vec3(0.2f, 0.5f, 0.8f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.05f, 0.9f, 0.3f)}) {
      Vec3 a = cs().convert(v, "lin_rec709", space);
      Vec3 b = cs().convert(a, space, "lin_rec709");
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], v[c], 1e-5f) << space;
    }
  }
}

// ACEScg: lin_rec709 (1,0,0) -> AP1 (0.61310, 0.07019, 0.02062) (Bradford D65->D60;
// values of the standard sRGB -> ACEScg matrix), white stays white.
TEST(Color, AcescgMatrix) {
  Vec3 r = cs().convert(Vec3(1.0f, 0.0f, 0.0f), "lin_rec709", "acescg");
  EXPECT_NEAR(r.x, 0.61310f, 1e-4f);
  EXPECT_NEAR(r.y, 0.07019f, 1e-4f);
  EXPECT_NEAR(r.z, 0.02062f, 1e-4f);
  Vec3 w = cs().convert(Vec3(1.0f), "lin_rec709", "acescg");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[c], 1.0f, 1e-5f);
  Vec3 p = cs().convert(Vec3(1.0f, 0.0f, 0.0f), "lin_rec709", "display_p3");
  EXPECT_NEAR(p.x, 0.8225f, 1e-4f);  // standard sRGB -> Display P3 matrix
  EXPECT_NEAR(p.y, 0.0332f, 1e-4f);
  EXPECT_NEAR(p.z, 0.0171f, 1e-4f);
}

// The static matrix helpers agree with OCIO (1e-5).
TEST(Color, MatrixHelpersAgreeWithOcio) {
  Mat3 toXYZ = ColorSystem::rec709ToXYZ(), toRGB = ColorSystem::xyzToRec709();
  for (Vec3 v : {Vec3(0.2f, 0.5f, 0.8f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f)}) {
    Vec3 a = cs().convert(v, "lin_rec709", "cie_xyz_d65"), b = toXYZ * v;
    Vec3 c = cs().convert(v, "cie_xyz_d65", "lin_rec709"), d = toRGB * v;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(a[i], b[i], 1e-5f);
      EXPECT_NEAR(c[i], d[i], 1e-5f);
    }
  }
  Mat3 id = toRGB * toXYZ;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(id[i][j], i == j ? 1.0f : 0.0f, 1e-6f);
  // Generic helper reproduces the Rec.709 matrix.
  Mat3 g = rgbToXYZMatrix({0.64f, 0.33f}, {0.30f, 0.60f}, {0.15f, 0.06f}, {0.3127f, 0.3290f});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(g[i][j], toXYZ[i][j], 1e-6f);
}

TEST(Color, ConvertImage) {
  Image img(3, 2, {"R", "G", "B", "A"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      img.at(x, y, 0) = 0.1f * (x + 1);
      img.at(x, y, 1) = 0.2f * (y + 1);
      img.at(x, y, 2) = 0.5f;
      img.at(x, y, 3) = 0.7f;
    }
  Image ref = img;
  cs().convertImage(img, "lin_rec709", "srgb");
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y, c), srgbEncode(ref.at(x, y, c)), 1e-4f);
      EXPECT_EQ(img.at(x, y, 3), 0.7f);  // alpha untouched
    }
}

// convertImage works on bands of rows in parallel: a large image (many bands, a partial last
// one, an alpha channel) comes out the same at one thread as at several, and every pixel as
// the pixel converted alone.
TEST(Color, ConvertImageIsTheSameAtAnyThreadCount) {
  Image img(331, 97, {"R", "G", "B", "A"});
  Rng rng(3, 1);
  for (float& v : img.data) v = float(1.2 * rng.uniformDouble() - 0.1);
  Image one = img, many = img;
  {
    ThreadLimit limit(1);
    cs().convertImage(one, "cie_xyz_d65", "srgb");
  }
  {
    ThreadLimit limit(4);
    cs().convertImage(many, "cie_xyz_d65", "srgb");
  }
  EXPECT_EQ(one.data, many.data);
  for (int y : {0, 48, 96})
    for (int x : {0, 165, 330}) {
      const Vec3 alone = cs().convert(Vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)), "cie_xyz_d65", "srgb");
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(many.at(x, y, c), alone[c], 1e-5f);
      EXPECT_EQ(many.at(x, y, 3), img.at(x, y, 3));  // alpha untouched
    }
}

TEST(Color, UnknownSpaceIsInputError) {
  try {
    cs().convert(Vec3(1.0f), "lin_rec709", "no_such_space");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("no_such_space"), std::string::npos) << msg;
    EXPECT_NE(msg.find("acescg"), std::string::npos) << msg;
    EXPECT_NE(msg.find("config.ocio"), std::string::npos) << msg;
  }
}

TEST(Color, XyzToLab) {
  Vec3d white(0.95047, 1.0, 1.08883);
  Vec3d lab = xyzToLab(white);
  EXPECT_NEAR(lab.x, 100.0, 1e-9);
  EXPECT_NEAR(lab.y, 0.0, 1e-9);
  EXPECT_NEAR(lab.z, 0.0, 1e-9);
  // Y = 0.18 -> L* = 116 * 0.18^(1/3) - 16 = 49.4961.
  EXPECT_NEAR(xyzToLab(white * 0.18).x, 49.4961, 1e-4);
  // Linear segment: Y = 0.001 -> L* = 903.2963 * 0.001.
  EXPECT_NEAR(xyzToLab(white * 0.001).x, 0.9032963, 1e-6);
}

// Sharma, Wu & Dalal (2005), Table 1 test pairs, to 1e-4.
TEST(Color, Ciede2000SharmaPairs) {
  struct Pair { Vec3d a, b; double dE; };
  const Pair pairs[] = {
      {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
      {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
      {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
      {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
      {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
      {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
      {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
      {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
      {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
      {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
      {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
      {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
      {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
      {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
      {{90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
      {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
  };
  for (const auto& p : pairs) {
    EXPECT_NEAR(ciede2000(p.a, p.b), p.dE, 1e-4) << p.a.x << "," << p.a.y << "," << p.a.z;
    EXPECT_NEAR(ciede2000(p.b, p.a), p.dE, 1e-4);  // symmetric
  }
  EXPECT_EQ(ciede2000({50, 10, 10}, {50, 10, 10}), 0.0);
}

}  // namespace
}  // namespace inim

#include <thread>
#include <vector>

namespace inim {
namespace {
// Processors are cached and shared between threads: concurrent conversions agree.
TEST(Color, ConcurrentConversions) {
  std::vector<std::thread> threads;
  std::vector<float> results(8);
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([t, &results] {
      const char* spaces[] = {"acescg", "display_p3", "srgb", "cie_xyz_d65"};
      float acc = 0.0f;
      for (int i = 0; i < 200; ++i)
        acc += ColorSystem::instance().convert(Vec3(0.5f), "lin_rec709", spaces[(t + i) % 4]).y;
      results[t] = acc;
    });
  for (auto& th : threads) th.join();
  for (int t = 1; t < 8; ++t) EXPECT_NEAR(results[t], results[0], 1e-3f);
}
}  // namespace
}  // namespace inim
