// The sensor: white balance and the camera RGB -> XYZ fit.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/camera_config.h"
#include "camera/sensor.h"
#include "core/output_file.h"
#include "spectral/cie.h"
#include "spectral/color.h"

using namespace inim;

namespace {

// D65 scaled to luminance Y = 1.
std::shared_ptr<PiecewiseLinearSpectrum> d65Unit() {
  auto d = std::make_shared<PiecewiseLinearSpectrum>(cie::D65().lambdas(), cie::D65().values());
  d->scale(float(1.0 / spectrumToXYZ(*d).y));
  return d;
}

}  // namespace

TEST(Sensor, D65WhiteMapsToYOne) {
  CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  const CameraSensor& s = c.sensor;
  auto d65 = d65Unit();
  const Vec3d rgb = s.cameraRgb(*d65);
  EXPECT_NEAR(rgb.x, 1.0, 1e-3);
  EXPECT_NEAR(rgb.y, 1.0, 1e-3);
  EXPECT_NEAR(rgb.z, 1.0, 1e-3);
  const Vec3d xyz = s.toXyz(rgb);
  EXPECT_NEAR(xyz.y, 1.0, 1e-3);
  // D65 chromaticity (0.3127, 0.3290) and XYZ ~ (0.9505, 1, 1.0888).
  EXPECT_NEAR(xyz.x / (xyz.x + xyz.y + xyz.z), 0.3127, 1e-3);
  EXPECT_NEAR(xyz.y / (xyz.x + xyz.y + xyz.z), 0.3290, 1e-3);
  EXPECT_NEAR(xyz.x, 0.9505, 2e-3);
  EXPECT_NEAR(xyz.z, 1.0888, 2e-3);
  // The white-balance gains, relative to green, as a raw converter reports them.
  const Vec3d wb = s.colorFit().whiteBalance / s.colorFit().whiteBalance.y;
  EXPECT_GT(wb.x, 1.0);  // red needs more gain than green under D65
  std::printf("white balance (R, G, B) / G = %.4f, 1, %.4f\n", wb.x, wb.z);
}

TEST(Sensor, ColorFitResidual) {
  // Least squares on the training set, constrained to map white exactly. No 3x3 matrix maps a
  // real sensor exactly onto the CIE observer (the Luther condition fails), so the residual is
  // the sensor's metamerism: documented bound mean CIEDE2000 < 3.
  CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  const ColorFit& f = c.sensor.colorFit();
  EXPECT_EQ(f.trainingSpectra, int(colorTrainingReflectances().size()));
  EXPECT_GT(f.trainingSpectra, 60);
  EXPECT_LT(f.meanDeltaE00, 3.0);
  EXPECT_LT(f.maxDeltaE00, 12.0);
  EXPECT_NEAR((f.cameraToXyz * Vec3d(1.0)).y, 1.0, 1e-9);
  RecordProperty("mean_dE00", std::to_string(f.meanDeltaE00));
  RecordProperty("max_dE00", std::to_string(f.maxDeltaE00));
  std::printf("camera RGB -> XYZ fit (sony_ilce_7rm3 curves, %d reflectances under D65): mean dE00 %.3f, max %.3f, "
              "RMS XYZ %.4f\n", f.trainingSpectra, f.meanDeltaE00, f.maxDeltaE00, f.rmsXyz);
  // The other measured camera fits comparably.
  auto r = loadSpectrumCSV(dataPath("spectra/camera_canon_eos_5d_mkiv.csv"), "r");
  auto g = loadSpectrumCSV(dataPath("spectra/camera_canon_eos_5d_mkiv.csv"), "g");
  auto b = loadSpectrumCSV(dataPath("spectra/camera_canon_eos_5d_mkiv.csv"), "b");
  ColorFit canon = fitCameraRgbToXyz(*r, *g, *b);
  EXPECT_LT(canon.meanDeltaE00, 4.0);
  std::printf("canon_eos_5d_mkiv: mean dE00 %.3f, max %.3f\n", canon.meanDeltaE00, canon.maxDeltaE00);
}

TEST(Sensor, LutherSensorFitsExactly) {
  // Sensitivities that are a linear combination of the CMFs satisfy the Luther condition:
  // the fit must then be exact (zero colour error).
  std::vector<float> l, vr, vg, vb;
  for (int i = 360; i <= 830; ++i) {
    const float x = cie::X()(float(i)), y = cie::Y()(float(i)), z = cie::Z()(float(i));
    l.push_back(float(i));
    vr.push_back(0.8f * x + 0.3f * y);
    vg.push_back(0.1f * x + 0.9f * y + 0.05f * z);
    vb.push_back(0.02f * y + 0.7f * z);
  }
  PiecewiseLinearSpectrum r(l, vr), g(l, vg), b(l, vb);
  ColorFit f = fitCameraRgbToXyz(r, g, b);
  EXPECT_LT(f.meanDeltaE00, 1e-3);
  EXPECT_LT(f.rmsXyz, 1e-5);
}

TEST(Sensor, ResponseIsWhiteBalancedSensitivity) {
  CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  const CameraSensor& s = c.sensor;
  const Vec3d raw = s.rawResponse(520.0), bal = s.response(520.0);
  EXPECT_NEAR(raw.y, 1.0, 1e-6);  // the Sony curves peak at 1 in green at 520 nm
  EXPECT_NEAR(bal.y, raw.y * s.colorFit().whiteBalance.y, 1e-12);
  EXPECT_EQ(s.rawResponse(300.0), Vec3d(0.0));  // outside the table
}
