#pragma once
// The small real-MLA setup the panel-estimator tests share (test_footprint.cpp,
// test_quadrature.cpp, test_estimators.cpp), and the image statistics they compare with.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "core/parallel.h"
#include "mla_optics/real_mla.h"
#include "display_view/display_pose.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_camera.h"
#include "display_view/view_renderer.h"
#include "view_test_util.h"

namespace view_test {
using namespace inim;

// A small display behind a real refracting MLA (with cover glass: dispersive, 3 rays per
// sample), seen by a thin-lens camera of the default camera's f/4 and 12 mm focal length from
// 200 mm: each camera pixel covers a quarter of a lenslet, and the lens aperture spreads over
// about a panel pixel on the panel, like the default setup at --width 648.
struct RealSetup {
  static constexpr double P = 1.0, g = 4.0, D = 200.0;
  Display display;
  EiLayout layout;
  std::unique_ptr<PanelEmitter> panel;
  std::unique_ptr<MlaModel> mla;
  std::unique_ptr<ThinLensCameraModel> camera;
  // hex: a hex lattice of hexagonal lenslets (pointy-top cells, 6 x 5 of them) instead.
  explicit RealSetup(bool white = false, int W = 24, int H = 16, bool hex = false) {
    display = hex ? smallDisplay(5, 5, 20, 0.05, P, 3.3, g, 14) : smallDisplay(6, 4, 20, 0.05, P, 3.3, g);
    display.mla.radiusMm = 1.62;
    if (hex) {
      display.mla.lattice = Mla::Lattice::Hex;
      display.mla.aperture = Mla::Aperture::Hex;
    }
    display.panel.coverGlass = CoverGlass{0.3, "N-BK7"};
    layout = computeLayout(display);
    panel = std::make_unique<PanelEmitter>(display.panel, layout,
                                           white ? uniformEia(layout, 1, 1, 1) : patternEia(layout), "eia.exr", g);
    mla = makeRealMla(display, layout, g);
    SensorGeometry s;
    s.widthPx = W;
    s.heightPx = H;
    s.pitchMm = 6.0 / W * 12.0 / (D - 12.0);  // the 6 mm display fills the width
    ViewingPose pose;
    pose.eye = {0.0, 0.0, D};
    camera = std::make_unique<ThinLensCameraModel>(s, pose, 12.0, 4.0, D);
  }
  // The tolerances of the tests on this setup are stated at aperture grid 12.
  ViewResult render(PanelEstimator e, int spp, uint64_t seed = 1, double scale = 1.0,
                    const CameraModel* cam = nullptr, const MlaModel* otherMla = nullptr) const {
    ViewSettings s;
    s.spp = spp;
    s.seed = seed;
    s.progress = false;
    s.panelEstimator = e;
    s.footprintScale = scale;
    s.apertureGrid = 12;
    return renderView(cam ? *cam : *camera, defaultCamera().sensor, otherMla ? *otherMla : *mla, *panel,
                      layout.activeArea(), s);
  }
};

inline double rmse(const Image& a, const Image& b) {
  double se = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) se += double(a.data[i] - b.data[i]) * (a.data[i] - b.data[i]);
  return std::sqrt(se / double(a.data.size()));
}
inline double meanAll(const Image& a) {
  double s = 0.0;
  for (float v : a.data) s += v;
  return s / double(a.data.size());
}
// Mean of channel c over a block of pixels.
inline double blockMean(const Image& a, int x0, int y0, int w, int h, int c) {
  double s = 0.0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) s += a.at(x, y, c);
  return s / (double(w) * h);
}

// The default camera (real lens) 200 mm from the setup, 640 px wide: the small display covers
// ~40 x 27 pixels (a pixel ~0.15 mm of the MLA).
inline std::unique_ptr<CameraModel> realLensCameraAt200mm() {
  DisplayPose pose;
  pose.distanceMm = 200.0;
  ViewCameraOptions o;
  o.width = 640;
  return makeViewCamera(defaultCamera(), pose, o);
}

// The estimator's image of the setup is the same bit for bit on one and on two threads, and finite.
inline void expectBitIdenticalOnOneAndTwoThreads(const RealSetup& r, PanelEstimator e, int spp, uint64_t seed) {
  Image one, two;
  {
    ThreadLimit t(1);
    one = r.render(e, spp, seed).image;
  }
  {
    ThreadLimit t(2);
    two = r.render(e, spp, seed).image;
  }
  ASSERT_EQ(one.data.size(), two.data.size());
  EXPECT_EQ(std::memcmp(one.data.data(), two.data.data(), one.data.size() * sizeof(float)), 0);
  for (float v : one.data) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace view_test
