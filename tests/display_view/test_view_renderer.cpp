// The view simulation end to end on small displays: radiance through an ideal MLA, agreement
// of the spectral estimators (and of the dispersive code path), determinism across thread
// counts, the direction a reconstructed point moves when the display turns, out-of-view poses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/parallel.h"
#include "mla_optics/ideal_mla.h"
#include "mla_optics/real_mla.h"
#include "spectral/cie.h"
#include "display_view/display_pose.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_camera.h"
#include "display_view/view_renderer.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

class WhiteSpectrum final : public Spectrum {
 public:
  explicit WhiteSpectrum(const PanelEmitter& e) : e_(e) {}
  float operator()(float l) const override {
    return e_.averageChannelSpectrum(0, l) + e_.averageChannelSpectrum(1, l) + e_.averageChannelSpectrum(2, l);
  }
  float maxValue() const override { return 0.0f; }

 private:
  const PanelEmitter& e_;
};

// The tests here sample with the Footprint estimator (their tolerances were stated for it, and
// the visible-packet spectral sampling needs a sampled estimator).
ViewSettings footprintSettings(int spp) {
  ViewSettings s;
  s.spp = spp;
  s.progress = false;
  s.panelEstimator = PanelEstimator::Footprint;
  return s;
}

// Uniform white through an ideal MLA seen by a pinhole camera 2000 mm away whose pixels each
// cover exactly 2 x 2 lenslets; f is chosen so that each lenslet's footprint on the panel is
// exactly 5 x 5 panel pixels (the landing point moves by P |1 + g/D - g/f| = P/2 across a
// cell), so every pixel's exact value is the tile-averaged panel white.
struct WhiteSetup {
  static constexpr double D = 2000.0, g = 3.0, P = 1.0;
  Display display;
  EiLayout layout;
  std::unique_ptr<PanelEmitter> panel;
  std::unique_ptr<IdealLensletMla> mla;
  std::unique_ptr<PinholeCameraModel> camera;
  Vec3d expected;
  explicit WhiteSetup(bool coverGlass = false) {
    const double f = g / (1.5 + g / D);
    display = smallDisplay(8, 4, 10, 0.1, P, f, g);
    if (coverGlass) display.panel.coverGlass = CoverGlass{0.3, "N-BK7"};
    layout = computeLayout(display);
    panel = std::make_unique<PanelEmitter>(display.panel, layout, uniformEia(layout, 1, 1, 1), "white.exr", g);
    mla = std::make_unique<IdealLensletMla>(layout, P, f, g);
    ViewingPose pose;
    pose.eye = {0.0, 0.0, D};
    camera = pinholeCamera(pose, 4, 2, 0.01, 10.0);
    expected = defaultCamera().sensor.cameraRgb(WhiteSpectrum(*panel));
  }
  ViewResult render(SpectralSampling sampling, int spp, bool perWavelength = false) const {
    ViewSettings s = footprintSettings(spp);
    s.spectral = sampling;
    s.perWavelengthRays = perWavelength;
    return renderView(*camera, defaultCamera().sensor, *mla, *panel, layout.activeArea(), s);
  }
};

Vec3d imageMean(const Image& img) { return {mean(img, 0), mean(img, 1), mean(img, 2)}; }

}  // namespace

TEST(ViewRenderer, UniformWhiteThroughIdealMlaIsPanelWhite) {
  WhiteSetup w;
  ViewResult r = w.render(SpectralSampling::Primaries, 4096);
  EXPECT_FALSE(r.stats.dispersive);
  EXPECT_EQ(r.stats.raysPerSample, 1);
  EXPECT_EQ(r.stats.displayRays, r.stats.tracedRays);  // every ray lands on the display
  // Radiance is conserved through the ideal lenses: each pixel sees the panel white (x the MLA
  // fill factor, 1 for the ideal MLA's square cells).
  const Vec3d m = imageMean(r.image);
  std::printf("[ measured ] uniform white / panel white (camera RGB): %.5f %.5f %.5f\n", m.x / w.expected.x,
              m.y / w.expected.y, m.z / w.expected.z);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(m[c] / w.expected[c], 1.0, 0.01) << "channel " << c;
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x)
        EXPECT_NEAR(r.image.at(x, y, c) / w.expected[c], 1.0, 0.03) << x << "," << y << " channel " << c;
  }
  // The panel white in camera RGB is the panel's luminance: ~ (600, 600, 600) for a white-ish
  // spectrum (camera RGB is white balanced to D65 of luminance 1).
  EXPECT_NEAR(defaultCamera().sensor.toXyz(w.expected).y, w.display.panel.peakLuminanceCdM2,
              0.1 * w.display.panel.peakLuminanceCdM2);
}

TEST(ViewRenderer, SpectralEstimatorsAgree) {
  WhiteSetup w;
  const Vec3d prim = imageMean(w.render(SpectralSampling::Primaries, 2048).image);
  const Vec3d vis = imageMean(w.render(SpectralSampling::Visible, 2048).image);
  const Vec3d prim3 = imageMean(w.render(SpectralSampling::Primaries, 2048, true).image);
  const Vec3d vis4 = imageMean(w.render(SpectralSampling::Visible, 2048, true).image);
  std::printf("[ measured ] G channel / panel white: primaries %.4f, visible %.4f, primaries 3 rays %.4f, visible 4 "
              "rays %.4f\n", prim.y / w.expected.y, vis.y / w.expected.y, prim3.y / w.expected.y, vis4.y / w.expected.y);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(vis[c] / w.expected[c], 1.0, 0.02) << "visible, channel " << c;
    EXPECT_NEAR(prim3[c] / w.expected[c], 1.0, 0.02) << "primaries, ray per primary, channel " << c;
    EXPECT_NEAR(vis4[c] / w.expected[c], 1.0, 0.03) << "visible, ray per wavelength, channel " << c;
    EXPECT_NEAR(prim[c] / w.expected[c], 1.0, 0.01) << "primaries, channel " << c;
  }
}

TEST(ViewRenderer, DispersiveCoverGlassEstimatorsAgree) {
  WhiteSetup w(true);
  ViewResult a = w.render(SpectralSampling::Primaries, 2048);
  ViewResult b = w.render(SpectralSampling::Visible, 2048);
  EXPECT_TRUE(a.stats.dispersive);
  EXPECT_EQ(a.stats.raysPerSample, 3);
  EXPECT_EQ(b.stats.raysPerSample, 4);
  const Vec3d ma = imageMean(a.image), mb = imageMean(b.image);
  std::printf("[ measured ] cover glass, primaries / visible: %.4f %.4f %.4f; / bare panel white: %.4f %.4f %.4f\n",
              ma.x / mb.x, ma.y / mb.y, ma.z / mb.z, ma.x / w.expected.x, ma.y / w.expected.y, ma.z / w.expected.z);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(ma[c] / mb[c], 1.0, 0.03) << "channel " << c;
    // The glass only loses a little to Fresnel reflection at these angles.
    EXPECT_GT(ma[c] / w.expected[c], 0.85);
    EXPECT_LT(ma[c] / w.expected[c], 1.05);
  }
}

TEST(ViewRenderer, BitIdenticalOnOneAndTwoThreads) {
  Display d = smallDisplay(12, 8, 20, 0.05, 1.0, 3.3, 4.0);
  d.mla.radiusMm = 1.62;
  d.panel.coverGlass = CoverGlass{0.3, "N-BK7"};
  const EiLayout L = computeLayout(d);
  Image eia = uniformEia(L, 0, 0, 0);
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x)
      for (int c = 0; c < 3; ++c) eia.at(x, y, c) = float(((x * 7 + y * 3 + c * 5) % 11) / 10.0);
  PanelEmitter panel(d.panel, L, eia, "eia.exr", 4.0);
  auto mla = makeRealMla(d, L, 4.0);
  ASSERT_TRUE(mla->isDispersive());
  DisplayPose pose{5.0, -3.0, 200.0};
  auto cam = pinholeCamera(pose.cameraPose(), 40, 24, 0.01, 20.0, true);
  for (SpectralSampling sm : {SpectralSampling::Primaries, SpectralSampling::Visible}) {
    ViewSettings s = footprintSettings(6);
    s.spectral = sm;
    s.seed = 42;
    Image one, two;
    {
      ThreadLimit t(1);
      one = renderView(*cam, defaultCamera().sensor, *mla, panel, L.activeArea(), s).image;
    }
    {
      ThreadLimit t(2);
      two = renderView(*cam, defaultCamera().sensor, *mla, panel, L.activeArea(), s).image;
    }
    ASSERT_EQ(one.data.size(), two.data.size());
    EXPECT_EQ(std::memcmp(one.data.data(), two.data.data(), one.data.size() * sizeof(float)), 0)
        << spectralSamplingName(sm);
    double sum = 0.0;
    for (float v : one.data) {
      ASSERT_TRUE(std::isfinite(v));
      sum += v;
    }
    EXPECT_GT(sum, 0.0);
    // Another seed gives another image.
    s.seed = 43;
    Image other = renderView(*cam, defaultCamera().sensor, *mla, panel, L.activeArea(), s).image;
    EXPECT_NE(std::memcmp(one.data.data(), other.data.data(), one.data.size() * sizeof(float)), 0);
  }
}

namespace {

// A display whose EIA reconstructs one white point on the axis at the ideal MLA's image
// distance L = g f / (g - f) in front of the MLA: each lenslet c lights a 3 x 3 pixel box centred
// on c (1 + g / L), the panel point that images to (0, 0, L), when it lies in c's own EI.
struct PointSetup {
  static constexpr double P = 2.0, f = 3.3, g = 4.0, pix = 0.05;
  Display display;
  EiLayout layout;
  std::unique_ptr<PanelEmitter> panel;
  std::unique_ptr<IdealLensletMla> mla;
  double Limg = g * f / (g - f);
  PointSetup() {
    display = smallDisplay(15, 15, 40, pix, P, f, g);
    layout = computeLayout(display);
    Image eia = uniformEia(layout, 0, 0, 0);
    for (int k = 0; k < layout.eiCols; ++k)
      for (int l = 0; l < layout.eiRows; ++l) {
        const double qx = layout.lensX[size_t(k)] * (1.0 + g / Limg), qy = layout.lensY[size_t(l)] * (1.0 + g / Limg);
        // Only where that panel point lies inside the lenslet's own EI.
        if (std::abs(qx - layout.lensX[size_t(k)]) > 0.5 * P - 2 * pix ||
            std::abs(qy - layout.lensY[size_t(l)]) > 0.5 * P - 2 * pix)
          continue;
        // A 3-pixel box centred exactly on q, drive = the box's coverage of each pixel.
        const double u = qx / pix + 0.5 * layout.eiaW, v = 0.5 * layout.eiaH - qy / pix;
        for (int row = int(v) - 3; row <= int(v) + 3; ++row)
          for (int col = int(u) - 3; col <= int(u) + 3; ++col) {
            const double cu = std::max(0.0, std::min(col + 1.0, u + 1.5) - std::max(double(col), u - 1.5));
            const double cv = std::max(0.0, std::min(row + 1.0, v + 1.5) - std::max(double(row), v - 1.5));
            for (int c = 0; c < 3; ++c)
              eia.at(col + layout.panelCol0, row + layout.panelRow0, c) += float(cu * cv);
          }
      }
    panel = std::make_unique<PanelEmitter>(display.panel, layout, eia, "point.exr", g);
    mla = std::make_unique<IdealLensletMla>(layout, P, f, g);
  }
  // Luminance-weighted centroid (continuous pixel coordinates) seen from a pose.
  Vec2d centroid(const DisplayPose& pose, int W, double pitch, double d) const {
    auto cam = pinholeCamera(pose.cameraPose(), W, W, pitch, d);
    const ViewSettings s = footprintSettings(64);
    ViewResult r = renderView(*cam, defaultCamera().sensor, *mla, *panel, layout.activeArea(), s);
    double sx = 0, sy = 0, sw = 0;
    for (int y = 0; y < W; ++y)
      for (int x = 0; x < W; ++x) {
        const double v = r.image.at(x, y, 0) + r.image.at(x, y, 1) + r.image.at(x, y, 2);
        sx += v * (x + 0.5);
        sy += v * (y + 0.5);
        sw += v;
      }
    EXPECT_GT(sw, 0.0);
    return {sx / sw, sy / sw};
  }
};

}  // namespace

TEST(ViewRenderer, TurningTheDisplayMovesAPointInFrontTheExpectedWay) {
  PointSetup ps;
  const int W = 64;
  const double D = 300.0, d = 20.0, pitch = 16.0 * d / D / W;
  // Where the camera model (pinhole at D, looking down -z, y up) sees a world point.
  auto project = [&](const Vec3d& p) {
    return Vec2d(0.5 * W + d * p.x / (D - p.z) / pitch, 0.5 * W - d * p.y / (D - p.z) / pitch);
  };
  const Vec2d c0 = ps.centroid({0.0, 0.0, D}, W, pitch, d);
  EXPECT_NEAR(c0.x, 0.5 * W, 0.3);
  EXPECT_NEAR(c0.y, 0.5 * W, 0.3);
  // +7 deg H: the display's normal swings toward +x (its right edge moves away), so a point in
  // front of the display moves to the right in the image: world (L sin 7, 0, L cos 7).
  const double a = 7.0 * M_PI / 180.0;
  const Vec2d cp = ps.centroid({7.0, 0.0, D}, W, pitch, d);
  const Vec2d ep = project({ps.Limg * std::sin(a), 0.0, ps.Limg * std::cos(a)});
  EXPECT_GT(cp.x, c0.x + 5.0);
  EXPECT_NEAR(cp.x, ep.x, 1.0);
  EXPECT_NEAR(cp.y, ep.y, 0.5);
  std::printf("[ measured ] point at z = %.3f mm: centroid x %.3f px at 0 deg, %.3f px at +7 deg H (expected %.3f)\n",
              ps.Limg, c0.x, cp.x, ep.x);
  const Vec2d cm = ps.centroid({-7.0, 0.0, D}, W, pitch, d);
  EXPECT_NEAR(cm.x, project({-ps.Limg * std::sin(a), 0.0, ps.Limg * std::cos(a)}).x, 1.0);
  // +7 deg V: the top edge moves away, the normal swings toward +y: the point moves up (row -).
  const Vec2d cv = ps.centroid({0.0, 7.0, D}, W, pitch, d);
  const Vec2d ev = project({0.0, ps.Limg * std::sin(a), ps.Limg * std::cos(a)});
  std::printf("[ measured ] centroid y %.3f px at 0 deg, %.3f px at +7 deg V (expected %.3f)\n", c0.y, cv.y, ev.y);
  EXPECT_LT(cv.y, c0.y - 5.0);
  EXPECT_NEAR(cv.y, ev.y, 1.0);
  EXPECT_NEAR(cv.x, ev.x, 0.5);
}

TEST(ViewRenderer, OutOfViewPoseSeesOnlyTheBackground) {
  WhiteSetup w;
  DisplayPose pose{120.0, 0.0, 2000.0};  // the camera is behind the display's plane
  auto cam = pinholeCamera(pose.cameraPose(), 4, 2, 0.01, 10.0);
  EXPECT_EQ(displayCoverage(*cam, w.layout.activeArea()), 0.0);
  ViewSettings s = footprintSettings(16);
  s.backgroundY = 0.25;
  ViewResult r = renderView(*cam, defaultCamera().sensor, *w.mla, *w.panel, w.layout.activeArea(), s);
  EXPECT_FALSE(r.stats.displayInView());
  for (float v : r.image.data) EXPECT_NEAR(v, 0.25, 1e-6);  // a D65 grey of Y = 0.25 is (Y, Y, Y)
  // Facing the display: fully covered.
  EXPECT_EQ(displayCoverage(*w.camera, w.layout.activeArea()), 1.0);
}

TEST(ViewRenderer, TileCullingChangesNothing) {
  WhiteSetup w;
  // A wide view: 96 x 64 pixels of 0.5 mm at the display (48 x 32 mm) around the 8 x 4 mm display,
  // seen at an angle.
  DisplayPose pose{20.0, -10.0, 2000.0};
  auto cam = pinholeCamera(pose.cameraPose(), 96, 64, 0.0025, 10.0);
  ViewSettings s = footprintSettings(8);
  ViewResult on = renderView(*cam, defaultCamera().sensor, *w.mla, *w.panel, w.layout.activeArea(), s);
  s.cullTiles = false;
  ViewResult off = renderView(*cam, defaultCamera().sensor, *w.mla, *w.panel, w.layout.activeArea(), s);
  EXPECT_GT(on.stats.culledPixels, 96u * 64u / 2);
  EXPECT_EQ(off.stats.culledPixels, 0u);
  EXPECT_GT(on.stats.displayRays, 0u);
  ASSERT_EQ(on.image.data.size(), off.image.data.size());
  EXPECT_EQ(std::memcmp(on.image.data.data(), off.image.data.data(), on.image.data.size() * sizeof(float)), 0);
}

TEST(ViewRenderer, BadSettingsAreInputErrors) {
  WhiteSetup w;
  ViewSettings s = footprintSettings(0);
  EXPECT_THROW(renderView(*w.camera, defaultCamera().sensor, *w.mla, *w.panel, w.layout.activeArea(), s),
               InputError);
  s.spp = 1;
  s.backgroundY = -1.0;
  EXPECT_THROW(renderView(*w.camera, defaultCamera().sensor, *w.mla, *w.panel, w.layout.activeArea(), s),
               InputError);
}

TEST(ViewCamera, ImageSizeScalesThePixelPitch) {
  const CameraDescription& c = defaultCamera();
  const SensorGeometry full = c.sensor.geometry();
  SensorGeometry g = viewSensorGeometry(c, full.widthPx / 4, 0);
  EXPECT_EQ(g.widthPx, full.widthPx / 4);
  EXPECT_EQ(g.heightPx, full.heightPx / 4);
  EXPECT_NEAR(g.pitchMm, 4.0 * full.pitchMm, 1e-12);
  EXPECT_NEAR(g.widthMm(), full.widthMm(), 1e-9);
  EXPECT_EQ(viewSensorGeometry(c, 0, 0).widthPx, full.widthPx);
  EXPECT_EQ(viewSensorGeometry(c, 100, 20).heightPx, 20);
  EXPECT_THROW(viewSensorGeometry(c, -3, 0), InputError);
  // The pinhole stand-in frames like the real lens: the same horizontal field of view.
  ViewCameraOptions o;
  o.kind = CameraModelKind::Pinhole;
  o.width = 64;
  auto pin = makeViewCamera(c, DisplayPose{}, o);
  EXPECT_EQ(pin->width(), 64);
  EXPECT_NEAR(pin->horizontalFovDeg(), 26.0, 1.5);
}
