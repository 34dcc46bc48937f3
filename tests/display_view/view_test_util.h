#pragma once
// Shared helpers for the view-stage tests: small displays, uniform and patterned EIAs, small
// pinhole cameras and the camera sensor of the default camera description.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "fixtures.h"
#include "camera/camera_config.h"
#include "camera/camera_model.h"
#include "core/image.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "display/panel.h"

namespace view_test {

using namespace inim;
namespace fs = std::filesystem;

inline fs::path scratchDir() { return fs::temp_directory_path() / ("inim_test_view_" + std::to_string(getpid())); }
inline std::string scratchPath(const std::string& name) {
  fs::path dir = scratchDir();
  fs::create_directories(dir);
  return (dir / name).string();
}
struct ScratchCleanup {
  ~ScratchCleanup() {
    std::error_code ec;
    fs::remove_all(scratchDir(), ec);
  }
};

// A small display on the default panel's primaries and the default MLA's material: K x R EIs
// of n x n pixels of `pixelMm`, lens pitch P (default: the EI pitch), focal length f,
// reconstruction gap g, panel `border` px larger than the EIA on each side, no cover glass,
// RGB stripe with fill factor 0.8.
inline Display smallDisplay(int K, int R, int n, double pixelMm, double P, double f, double g, int border = 4) {
  // The MLA tests' display without cover glass, with RGB stripes of 80% fill.
  Display d = fixtures::lensletTestDisplay({K, R, n, pixelMm, P, f, g, border});
  d.panel.file = "small-test-panel";
  d.panel.coverGlass.reset();
  d.panel.subpixels = rgbStripeLayout(0.8);
  return d;
}

// A panel-sized drive image, every pixel (r, g, b).
inline Image uniformEia(const EiLayout& L, float r, float g, float b) {
  Image img(L.panelW, L.panelH, {"R", "G", "B"});
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x) {
      img.at(x, y, 0) = r;
      img.at(x, y, 1) = g;
      img.at(x, y, 2) = b;
    }
  return img;
}

// A patterned panel-sized EIA: values from 0 to 1 that change from pixel to pixel and channel
// to channel (the hardest case for a panel estimator: every subpixel differs).
inline Image patternEia(const EiLayout& L) {
  Image eia = uniformEia(L, 0, 0, 0);
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x)
      for (int c = 0; c < 3; ++c) eia.at(x, y, c) = float(((x * 7 + y * 3 + c * 5) % 11) / 10.0);
  return eia;
}

// The default camera description (its sensor curves give the camera RGB).
inline const CameraDescription& defaultCamera() {
  static const CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  return c;
}

// A pinhole camera at `pose` (display frame) with a W x H sensor of `pitchMm` pixels at image
// distance `d`; natural vignetting off unless asked.
inline std::unique_ptr<PinholeCameraModel> pinholeCamera(const ViewingPose& pose, int W, int H, double pitchMm,
                                                         double d, bool vignetting = false) {
  SensorGeometry s;
  s.widthPx = W;
  s.heightPx = H;
  s.pitchMm = pitchMm;
  return std::make_unique<PinholeCameraModel>(s, pose, d, vignetting);
}

inline double mean(const Image& img, int c) {
  double s = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) s += img.at(x, y, c);
  return s / (double(img.width) * img.height);
}

}  // namespace view_test
