// RGB -> spectrum (Jakob & Hanika 2019) round trips under D65, compared in CIELAB.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "spectral/cie.h"
#include "spectral/color.h"
#include "spectral/rgb_to_spectrum.h"

namespace inim {
namespace {

// Linear rec709 of a reflectance under D65 (white Y = 1), through the 3x3 matrix.
Vec3d roundTripRGB(const Spectrum& s) {
  Vec3d xyz = reflectanceToXYZ(s, cie::D65());
  return glm::dmat3(ColorSystem::xyzToRec709()) * xyz;
}

double deltaE(const Vec3d& rgbA, const Vec3d& rgbB) {
  glm::dmat3 M(ColorSystem::rec709ToXYZ());
  return ciede2000(xyzToLab(M * rgbA), xyzToLab(M * rgbB));
}

TEST(RGBToSpectrum, TableBuildsOrLoads) {
  const auto& t = RGBToSpectrumTable::rec709();
  EXPECT_EQ(t.resolution(), RGBToSpectrumTable::kResolution);
  std::cout << "[ info ] table " << (t.loadedFromCache() ? "loaded from cache" : "optimised in ")
            << (t.loadedFromCache() ? std::string() : std::to_string(t.buildSeconds()) + " s")
            << " (" << t.cacheFile() << ")\n";
}

// X-Rite ColorChecker Classic, published sRGB (D65) 8-bit values, patches 1-24.
const int kColorChecker[24][3] = {
    {115, 82, 68},   {194, 150, 130}, {98, 122, 157},  {87, 108, 67},   {133, 128, 177},
    {103, 189, 170}, {214, 126, 44},  {80, 91, 166},   {193, 90, 99},   {94, 60, 108},
    {157, 188, 64},  {224, 163, 46},  {56, 61, 150},   {70, 148, 73},   {175, 54, 60},
    {231, 199, 31},  {187, 86, 149},  {8, 133, 161},   {243, 243, 242}, {200, 200, 200},
    {160, 160, 160}, {122, 122, 121}, {85, 85, 85},    {52, 52, 52}};

// Tolerance: CIEDE2000 < 0.5 (well below a just-noticeable difference of ~1).
TEST(RGBToSpectrum, ColorCheckerRoundTripUnderD65) {
  double worst = 0.0;
  for (const auto& p : kColorChecker) {
    Vec3 rgb(srgbDecode(p[0] / 255.0f), srgbDecode(p[1] / 255.0f), srgbDecode(p[2] / 255.0f));
    RGBAlbedoSpectrum s(rgb);
    double dE = deltaE(Vec3d(rgb), roundTripRGB(s));
    EXPECT_LT(dE, 0.5) << p[0] << "," << p[1] << "," << p[2];
    worst = std::max(worst, dE);
  }
  std::cout << "[ info ] ColorChecker worst CIEDE2000 = " << worst << "\n";
}

TEST(RGBToSpectrum, GridRoundTripUnderD65) {
  double worst = 0.0, sum = 0.0;
  Vec3 worstRgb(0.0f);
  int n = 0;
  for (int r = 0; r < 8; ++r)
    for (int g = 0; g < 8; ++g)
      for (int b = 0; b < 8; ++b) {
        Vec3 rgb(r / 7.0f, g / 7.0f, b / 7.0f);
        RGBAlbedoSpectrum s(rgb);
        double dE = deltaE(Vec3d(rgb), roundTripRGB(s));
        EXPECT_LT(dE, 0.5) << rgb.x << "," << rgb.y << "," << rgb.z;
        if (dE > worst) worst = dE, worstRgb = rgb;
        sum += dE;
        ++n;
      }
  std::cout << "[ info ] 8x8x8 grid worst CIEDE2000 = " << worst << " at (" << worstRgb.x << ","
            << worstRgb.y << "," << worstRgb.z << "), mean " << sum / n << "\n";
}

// A perfect white stays 1 at every wavelength (to 1e-3), black 0.
TEST(RGBToSpectrum, WhiteAndBlackAlbedo) {
  RGBAlbedoSpectrum white(Vec3(1.0f)), black(Vec3(0.0f)), grey(Vec3(0.5f));
  for (float l = kLambdaMin; l <= kLambdaMax; l += 1.0f) {
    EXPECT_NEAR(white(l), 1.0f, 1e-3f);
    EXPECT_NEAR(black(l), 0.0f, 1e-6f);
    EXPECT_NEAR(grey(l), 0.5f, 1e-6f);
  }
}

// Reflectances stay in [0, 1] for any input, including out-of-range rgb.
TEST(RGBToSpectrum, AlbedoIsBounded) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.2f, 1.2f);
  for (int i = 0; i < 500; ++i) {
    RGBAlbedoSpectrum s(Vec3(u(rng), u(rng), u(rng)));
    EXPECT_LE(s.maxValue(), 1.0f);
    for (float l = kLambdaMin; l <= kLambdaMax; l += 10.0f) {
      float v = s(l);
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
    }
  }
}

// rgb = (1,1,1) as an illuminant is D65 with Y = 1; other rgbs round-trip as emission.
TEST(RGBToSpectrum, IlluminantSpectrum) {
  RGBIlluminantSpectrum w(Vec3(1.0f));
  Vec3d xyz = spectrumToXYZ(w);
  EXPECT_NEAR(xyz.y, 1.0, 1e-5);
  Vec3d d65 = spectrumToXYZ(cie::D65());
  d65 /= d65.y;
  EXPECT_NEAR(xyz.x, d65.x, 1e-5);
  EXPECT_NEAR(xyz.z, d65.z, 1e-5);
  for (Vec3 rgb : {Vec3(0.8f, 0.2f, 0.1f), Vec3(0.1f, 0.5f, 0.9f), Vec3(3.0f, 2.0f, 0.5f)}) {
    RGBIlluminantSpectrum s(rgb);
    Vec3d back = glm::dmat3(ColorSystem::xyzToRec709()) * spectrumToXYZ(s);
    EXPECT_LT(deltaE(Vec3d(rgb) / double(maxComponent(rgb)), back / double(maxComponent(rgb))), 0.5);
  }
}

// Unbounded spectra: scale = 2 max(rgb), as pbrt-v4; the rgb round-trips under D65.
TEST(RGBToSpectrum, UnboundedSpectrum) {
  Vec3 rgb(2.0f, 1.0f, 0.5f);
  RGBUnboundedSpectrum s(rgb);
  EXPECT_NEAR(s.maxValue(), 4.0f * RGBToSpectrumTable::rec709()(rgb / 4.0f).maxValue(), 1e-5f);
  Vec3d back = roundTripRGB(s);
  EXPECT_LT(deltaE(Vec3d(rgb) / 2.0, back / 2.0), 0.5);
  RGBUnboundedSpectrum zero(Vec3(0.0f));
  EXPECT_EQ(zero(550.0f), 0.0f);
}

// Direct Gauss-Newton fits agree with the interpolated table (same colour to dE < 0.5).
TEST(RGBToSpectrum, DirectFitMatchesTable) {
  for (Vec3 rgb : {Vec3(0.9f, 0.1f, 0.05f), Vec3(0.2f, 0.7f, 0.3f), Vec3(0.05f, 0.1f, 0.8f)}) {
    SigmoidPolynomial p = RGBToSpectrumTable::fit(rgb);
    struct S final : Spectrum {
      SigmoidPolynomial p;
      float operator()(float l) const override { return p(l); }
      float maxValue() const override { return p.maxValue(); }
    } s;
    s.p = p;
    EXPECT_LT(deltaE(Vec3d(rgb), roundTripRGB(s)), 0.05);
  }
}

// A damaged cache file is recomputed; a good one is loaded.
TEST(RGBToSpectrum, CacheIsValidated) {
  RGBToSpectrumTable::rec709();  // initialised before the cache folder changes
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("inim-test-cache-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const char* old = std::getenv("INIM_CACHE_DIR");
  std::string oldValue = old ? old : "";
  setenv("INIM_CACHE_DIR", dir.c_str(), 1);
  const int res = 6;
  std::string path = RGBToSpectrumTable::cachePath(res);
  EXPECT_EQ(fs::path(path).parent_path(), dir);
  { std::ofstream(path, std::ios::binary) << "garbage"; }
  auto a = RGBToSpectrumTable::loadOrCompute(res);
  EXPECT_FALSE(a.loadedFromCache());
  auto b = RGBToSpectrumTable::loadOrCompute(res);
  EXPECT_TRUE(b.loadedFromCache());
  Vec3 rgb(0.3f, 0.6f, 0.2f);
  EXPECT_EQ(a(rgb).c0, b(rgb).c0);
  EXPECT_EQ(a(rgb).c2, b(rgb).c2);
  fs::resize_file(path, fs::file_size(path) - 4);  // truncated
  EXPECT_FALSE(RGBToSpectrumTable::loadOrCompute(res).loadedFromCache());
  if (old) setenv("INIM_CACHE_DIR", oldValue.c_str(), 1);
  else unsetenv("INIM_CACHE_DIR");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace inim

namespace inim {
namespace {
// Non-finite or negative input never reads outside the table and gives a valid spectrum.
TEST(RGBToSpectrum, NonFiniteInputIsSafe) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (Vec3 rgb : {Vec3(nan, 0.5f, 0.2f), Vec3(-1.0f, 0.5f, 0.2f), Vec3(inf, 0.5f, 0.2f)}) {
    RGBAlbedoSpectrum a(rgb);
    float v = a(550.0f);
    EXPECT_TRUE(v >= 0.0f && v <= 1.0f);
  }
  RGBUnboundedSpectrum u(Vec3(nan, -2.0f, 0.0f));
  EXPECT_EQ(u(550.0f), 0.0f);
}
}  // namespace
}  // namespace inim
