// Focus by moving the sensor, f-number control, pupils, spot size, and the lens report.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/camera_config.h"
#include "camera/lens_analysis.h"
#include "camera/lens_focus.h"
#include "camera/lens_loader.h"
#include "camera_test_util.h"

using namespace inim;

TEST(LensFocus, SensorShiftFollowsNewtonsEquation) {
  // x x' = f^2: an object x in front of the front focal point images x' = f^2 / x behind the
  // rear focal point, so the sensor moves from the infinity focus (BFL) by f^2 / x.
  for (const char* name : {"dgauss.50mm", "telephoto.250mm", "edmund-85-351-standin"}) {
    LensSystem lens = loadLens(name);
    const LensInfo info = analyzeLens(lens);
    for (double x : {350.0, 1000.0}) {
      const double objectZ = -info.fflMm - x;  // F sits FFL in front of the first vertex
      const double d = focusSensorDistance(lens, objectZ, FocusMode::Paraxial);
      const double shift = d - info.bflMm;
      const double newton = info.eflMm * info.eflMm / x;
      EXPECT_NEAR(shift / newton, 1.0, 0.01) << name << " x " << x;
      EXPECT_NEAR(shift / newton, 1.0, 1e-6) << name << " x " << x;  // paraxially exact
    }
    // Focus at infinity is the back focal length.
    EXPECT_NEAR(focusSensorDistance(lens, -INFINITY, FocusMode::Paraxial), info.bflMm, 1e-9);
  }
}

TEST(LensFocus, FNumberControlScalesTheStop) {
  LensSystem lens = loadLens("dgauss.50mm");
  const double widest = widestFNumber(lens);
  EXPECT_NEAR(widest, 2.03, 0.01);
  for (double N : {4.0, 2.8, 8.0, 16.0}) {
    setFNumber(lens, N);
    const LensInfo info = analyzeLens(lens);
    EXPECT_NEAR(info.eflMm / info.entrancePupil.diameterMm, N, 0.01 * N);
    EXPECT_NEAR(info.fNumber, N, 1e-6 * N);
    EXPECT_NEAR(info.eflMm, 50.358, 0.001);  // the stop does not change the focal length
  }
  InputError e = expectInputError([&] { setFNumber(lens, 1.4); });
  EXPECT_EQ(e.key(), "f_number");
  EXPECT_NE(e.expected().find("2.03"), std::string::npos) << e.what();
  expectInputError([&] { setFNumber(lens, 0.0); });
}

TEST(LensFocus, PupilsAreImagesOfTheStop) {
  for (const char* name : {"dgauss.50mm", "telephoto.250mm"}) {
    LensSystem lens = loadLens(name);
    const LensInfo info = analyzeLens(lens);
    const int stop = lens.stopIndex();
    TraceOptions upToStop;
    upToStop.apertures = false;
    upToStop.last = stop;
    auto stopHeight = [&](LensRay r) {
      std::vector<SurfaceHit> path;
      EXPECT_TRUE(lens.trace(r, 587.56, TraceDirection::ObjectToImage, upToStop, &path).ok());
      return path.back().p.y;
    };
    // A near-axis chief ray aimed at the entrance-pupil centre crosses the stop centre.
    const double a = 1e-4;
    const Vec3d d = glm::normalize(Vec3d(0.0, a, 1.0));
    const Point3d ep(0.0, 0.0, info.entrancePupil.positionMm);
    const double yChief = stopHeight({ep - 50.0 * d, d});
    const double yOff = stopHeight({ep + Vec3d(0.0, 0.01, 0.0) - 50.0 * d, d});
    EXPECT_LT(std::abs(yChief), 1e-4 * std::abs(yOff)) << name;
    // A ray parallel to the axis at a fraction e of the entrance-pupil radius reaches the stop
    // at the same fraction of the stop radius.
    const double e = 1e-4;
    const double y = stopHeight({{0.0, e * 0.5 * info.entrancePupil.diameterMm, -1.0}, {0.0, 0.0, 1.0}});
    EXPECT_NEAR(y / (e * 0.5 * lens.stopDiameterMm()), 1.0, 1e-6) << name;
    // Exit pupil: from the image side, a ray at a fraction e of the exit-pupil radius,
    // parallel to the axis, reaches the stop at that fraction of its radius.
    TraceOptions fromStop;
    fromStop.apertures = false;
    fromStop.first = stop;
    LensRay r{{0.0, e * 0.5 * info.exitPupil.diameterMm, lens.lastVertexZ() + 1.0}, {0.0, 0.0, -1.0}};
    std::vector<SurfaceHit> path;
    ASSERT_TRUE(lens.trace(r, 587.56, TraceDirection::ImageToObject, fromStop, &path).ok());
    EXPECT_NEAR(path.back().p.y / (e * 0.5 * lens.stopDiameterMm()), 1.0, 1e-6) << name;
  }
}

TEST(LensFocus, NearAxisPointFocusesWithinAPixel) {
  // The Alvium camera (stand-in lens, f/4) focused at 350 mm: a near-axis point at the focus
  // distance images to an RMS spot radius below one 2.2 um pixel.
  CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  RealLensCameraModel cam(c.lens, c.sensor.geometry(), defaultViewingPose(c),
                          [&] {
                            RealLensCameraModel::Settings s;
                            s.fNumber = c.fNumber;
                            s.focusDistanceMm = 350.0;
                            return s;
                          }());
  const double zObj = cam.lensInfo().entrancePupil.positionMm - 350.0;
  const double pixel = c.sensor.geometry().pitchMm;
  for (Point3d p : {Point3d(0.0, 0.0, zObj), Point3d(1.0, 0.5, zObj), Point3d(0.0, -3.0, zObj)}) {
    SpotDiagram s = spotDiagram(cam.lens(), p, cam.sensorDistanceMm(), 587.56, 41);
    EXPECT_GT(s.rays, 500);
    EXPECT_LT(s.rmsRadiusMm, pixel) << "point " << p.x << ", " << p.y;
    std::printf("spot at (%.1f, %.1f) mm on the display plane: RMS radius %.3f um (%d rays)\n", p.x, p.y,
                1e3 * s.rmsRadiusMm, s.rays);
  }
  // Paraxial focus is also within a pixel here; best-RMS focus is never worse.
  LensSystem lens = cam.lens();
  const double dPar = focusSensorDistance(lens, zObj, FocusMode::Paraxial);
  const double dBest = focusSensorDistance(lens, zObj, FocusMode::BestRms);
  const double rPar = spotDiagram(lens, {0, 0, zObj}, dPar).rmsRadiusMm;
  const double rBest = spotDiagram(lens, {0, 0, zObj}, dBest).rmsRadiusMm;
  EXPECT_LE(rBest, rPar * (1.0 + 1e-9));
  EXPECT_LT(rPar, pixel);
  // At f/2 the double Gauss has visible spherical aberration; best focus reduces it.
  LensSystem dg = loadLens("dgauss.50mm");
  const double p2 = spotDiagramAtInfinity(dg, {0, 0, 1}, focusSensorDistance(dg, -INFINITY, FocusMode::Paraxial)).rmsRadiusMm;
  const double b2 = spotDiagramAtInfinity(dg, {0, 0, 1}, focusSensorDistance(dg, -INFINITY, FocusMode::BestRms)).rmsRadiusMm;
  EXPECT_LT(b2, p2);
}

TEST(LensAnalysis, TextAndJsonReports) {
  LensSystem lens = loadLens("dgauss.50mm");
  Json j = lensInfoJson(lens);
  for (const char* k : {"efl_mm", "bfl_mm", "ffl_mm", "f_number", "entrance_pupil", "exit_pupil", "total_track_mm"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_TRUE(j["entrance_pupil"].contains("position_mm"));
  EXPECT_TRUE(j["exit_pupil"].contains("diameter_mm"));
  EXPECT_NEAR(j["efl_mm"].get<double>(), 50.36, 0.01);
  EXPECT_NEAR(j["total_track_mm"].get<double>(), j["length_mm"].get<double>() + j["bfl_mm"].get<double>(), 1e-9);
  // Principal planes: F' - P' = EFL.
  EXPECT_NEAR(j["bfl_mm"].get<double>() - j["rear_principal_plane_mm"].get<double>(), j["efl_mm"].get<double>(), 1e-9);
  const std::string t = lensInfoText(lens);
  EXPECT_NE(t.find("EFL"), std::string::npos);
  EXPECT_NE(t.find("50.358"), std::string::npos) << t;
  EXPECT_NE(t.find("Entrance pupil"), std::string::npos);
}
