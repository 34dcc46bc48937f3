// The chain's response through real renders: the linear model against a direct render of a
// patch, the observer-as-sensor, and a pose that cannot see the display.
#include <gtest/gtest.h>

#include "colour_chain/chain_response.h"
#include "colour_chain/patch_sets.h"
#include "fixtures.h"
#include "spectral/cie.h"

namespace inim {
namespace {

ChainOptics paperOptics() {
  ChainOptics o;
  o.display = loadDisplay(displayPathOrDefault(""));
  o.layout = computeLayout(o.display);
  o.camera = loadCameraDescription("alvium-1800-u-500c");
  return o;
}

ChainRenderSettings smallRender() {
  ChainRenderSettings s;
  s.width = 96;
  s.view.apertureGrid = 8;
  return s;
}

TEST(ChainResponse, ObserverSensorGivesXyz) {
  const CameraSensor obs = cieObserverSensor(SensorGeometry{64, 48, 0.01});
  const Vec3d d65 = obs.cameraRgb(ScaledSpectrum(std::make_shared<PiecewiseLinearSpectrum>(cie::D65()),
                                                 float(1.0 / spectrumToXYZ(cie::D65()).y)));
  EXPECT_NEAR(d65.x, 1.0, 1e-3);
  EXPECT_NEAR(d65.y, 1.0, 1e-3);
  EXPECT_NEAR(d65.z, 1.0, 1e-3);
  const GaussianSpectrum green(540.0f, 30.0f);
  const Vec3d xyz = obs.cameraRgb(green) * d65WhiteXyz();
  EXPECT_LT(glm::length(xyz - spectrumToXYZ(green)) / glm::length(xyz), 2e-3);
}

TEST(ChainResponse, LinearModelMatchesADirectRender) {
  const ChainOptics o = paperOptics();
  const ChainRenderSettings s = smallRender();
  const NamedPose pose = fig11Poses(7.0, o.camera.distanceMm)[2];  // H +7°
  const PoseResponse r = characterisePose(o, pose, s);
  EXPECT_GT(r.pixels, 300);
  EXPECT_LT(r.pixels, r.displayPixels);
  for (const Vec3d drive : {Vec3d(0.3, 0.6, 0.2), Vec3d(1.0, 0.05, 0.7)}) {
    const FlatPatchMeasurement m = renderFlatPatch(o, pose, drive, r.measured, s);
    EXPECT_LT(glm::length(m.xyz - r.xyz(drive)) / glm::length(m.xyz), 1e-5);
    EXPECT_LT(glm::length(m.cameraRgb - r.cameraRgb(drive)) / glm::length(m.cameraRgb), 1e-5);
  }
  // Through a lossless chain the panel white would measure Y = 1; the optics lose some light
  // (Fresnel at the MLA and the glass, the black matrix is area-normalised), never gain it.
  const double whiteY = (r.xyzPerDrive * Vec3d(1.0)).y;
  EXPECT_GT(whiteY, 0.5);
  EXPECT_LT(whiteY, 1.0);
}

TEST(ChainResponse, PoseThatCannotSeeTheDisplayIsAnInputError) {
  const ChainOptics o = paperOptics();
  const NamedPose away{"back", "back", DisplayPose{150.0, 0.0, o.camera.distanceMm}};  // sees its back
  const InputError e = fixtures::expectInputError([&] { characterisePose(o, away, smallRender()); });
  EXPECT_EQ(e.key(), "pose");
}

}  // namespace
}  // namespace inim
