// CIE colour matching functions, illuminants and spectrum -> XYZ.
#include <gtest/gtest.h>

#include "spectral/cie.h"

namespace inim {
namespace {

// The integral of y_bar over 360-830 nm is 106.857 (pbrt-v4's CIE_Y_integral 106.856895).
TEST(CIE, YIntegral) { EXPECT_NEAR(cie::yIntegral(), 106.856895, 1e-3); }

// D65 through the CIE 1931 CMFs: XYZ = (0.9505, 1, 1.0888) within 1e-3 (docs/design.md §5.1).
TEST(CIE, D65WhitePoint) {
  Vec3d xyz = spectrumToXYZ(cie::D65());
  xyz /= xyz.y;
  EXPECT_NEAR(xyz.x, 0.9505, 1e-3);
  EXPECT_NEAR(xyz.z, 1.0888, 1e-3);
  std::cout << "[ info ] D65 XYZ = (" << xyz.x << ", 1, " << xyz.z << ")\n";
}

// Illuminant A: xy = (0.44757, 0.40745), XYZ = (1.0985, 1, 0.3558) within 1e-3.
TEST(CIE, AWhitePoint) {
  Vec3d xyz = spectrumToXYZ(cie::A());
  xyz /= xyz.y;
  EXPECT_NEAR(xyz.x, 1.09850, 1e-3);
  EXPECT_NEAR(xyz.z, 0.35585, 1e-3);
}

// White furnace: a perfect reflector under D65 gives D65's normalised XYZ, Y exactly 1.
TEST(CIE, WhiteFurnaceReflectance) {
  Vec3d xyz = reflectanceToXYZ(ConstantSpectrum(1.0f), cie::D65());
  Vec3d d65 = spectrumToXYZ(cie::D65());
  d65 /= d65.y;
  EXPECT_NEAR(xyz.y, 1.0, 1e-6);
  EXPECT_NEAR(xyz.x, d65.x, 1e-6);
  EXPECT_NEAR(xyz.z, d65.z, 1e-6);
  // Linear in the reflectance.
  EXPECT_NEAR(reflectanceToXYZ(ConstantSpectrum(0.3f), cie::A()).y, 0.3, 1e-6);
}

// Equal-energy illuminant E (constant 1): Y = integral(y_bar) / yIntegral = 1 and
// X = Z = 1 to the precision of the CMF table (the CIE normalises them to equal areas).
TEST(CIE, IlluminantEIsEqualEnergy) {
  Vec3d xyz = spectrumToXYZ(ConstantSpectrum(1.0f));
  EXPECT_NEAR(xyz.y, 1.0, 1e-9);
  EXPECT_NEAR(xyz.x, 1.0, 2e-3);
  EXPECT_NEAR(xyz.z, 1.0, 2e-3);
}

TEST(CIE, CmfValues) {
  // Tabulated CIE 1931 values at 555 nm: y_bar = 1.0 (peak), x_bar = 0.5121, z_bar = 0.00575.
  EXPECT_NEAR(cie::Y()(555.0f), 1.0f, 1e-4f);
  EXPECT_NEAR(cie::X()(555.0f), 0.5121f, 1e-3f);
  EXPECT_NEAR(cie::Z()(555.0f), 0.00575f, 1e-4f);
  EXPECT_NEAR(cie::D65()(560.0f), 100.0f, 1e-3f);
}

}  // namespace
}  // namespace inim
