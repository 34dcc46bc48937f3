#include "colour_chain/chain_response.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "colour_chain/patch_sets.h"
#include "core/error.h"
#include "core/format.h"
#include "spectral/cie.h"
#include "display_view/display_model.h"
#include "display_view/view_camera.h"
#include "display_view/view_renderer.h"

namespace inim {

namespace {

// The EIA area filled with one drive value.
Image flatEia(const EiLayout& L, const Vec3d& drive) {
  Image img(L.eiaW, L.eiaH, {"R", "G", "B"});
  for (size_t i = 0; i < img.data.size(); i += 3)
    for (size_t c = 0; c < 3; ++c) img.data[i + c] = float(drive[int(c)]);
  return img;
}

EmitterSettings relativeEmitter(const ChainRenderSettings& s) {
  EmitterSettings e;
  e.absolute = false;  // panel white on axis Y = 1
  e.coverGlass = s.coverGlass;
  return e;
}

ViewSettings quietView(const ChainRenderSettings& s) {
  ViewSettings v = s.view;
  v.progress = false;
  return v;
}

Vec3d meanOver(const Image& img, const PixelMask& m) {
  Vec3d sum(0.0);
  int64_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (m.counts(x, y)) {
        const float* p = &img.data[(size_t(y) * size_t(img.width) + size_t(x)) * size_t(img.numChannels())];
        sum += Vec3d(p[0], p[1], p[2]);
        ++n;
      }
  return n > 0 ? sum / double(n) : sum;
}

// The display's pixels inside the central `fraction` of their bounding box.
PixelMask interiorOf(const PixelMask& display, double fraction) {
  int x0 = display.width, x1 = -1, y0 = display.height, y1 = -1;
  for (int y = 0; y < display.height; ++y)
    for (int x = 0; x < display.width; ++x)
      if (display.counts(x, y)) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  PixelMask m{display.width, display.height, std::vector<uint8_t>(display.on.size(), 0), "interior"};
  if (x1 < x0) return m;
  const double mx = 0.5 * (1.0 - fraction) * (x1 - x0), my = 0.5 * (1.0 - fraction) * (y1 - y0);
  for (int y = 0; y < display.height; ++y)
    for (int x = 0; x < display.width; ++x)
      if (display.counts(x, y) && x >= x0 + mx && x <= x1 - mx && y >= y0 + my && y <= y1 - my)
        m.on[size_t(y) * size_t(m.width) + size_t(x)] = 1;
  return m;
}

// Drops the pixels whose luminance lies outside the [p, 100 - p] percentiles.
void trimByLuminance(PixelMask& m, const std::vector<float>& luminance, double percent) {
  std::vector<float> values;
  for (size_t i = 0; i < m.on.size(); ++i)
    if (m.on[i]) values.push_back(luminance[i]);
  if (values.size() < 3 || percent <= 0.0) return;
  std::sort(values.begin(), values.end());
  const size_t k = size_t(std::floor(percent / 100.0 * double(values.size())));
  const float lo = values[k], hi = values[values.size() - 1 - k];
  for (size_t i = 0; i < m.on.size(); ++i)
    if (m.on[i] && !(luminance[i] >= lo && luminance[i] <= hi)) m.on[i] = 0;
}

// One view of a display model through a camera and a sensor.
struct PoseRig {
  std::unique_ptr<CameraModel> camera;
  CameraSensor observer;
};

PoseRig makeRig(const ChainOptics& o, const NamedPose& pose, const ChainRenderSettings& s) {
  ViewCameraOptions co;
  co.width = s.width;
  PoseRig rig;
  rig.camera = makeViewCamera(o.camera, pose.pose, co);
  rig.observer = cieObserverSensor(viewSensorGeometry(o.camera, s.width, 0));
  return rig;
}

}  // namespace

CameraSensor cieObserverSensor(const SensorGeometry& geometry) {
  auto table = [](const PiecewiseLinearSpectrum& s) { return std::make_shared<PiecewiseLinearSpectrum>(s); };
  return CameraSensor("CIE 1931 2° observer", geometry, table(cie::X()), table(cie::Y()), table(cie::Z()),
                      "spectra/cie1931_2deg_cmf.csv");
}

PoseResponse characterisePose(const ChainOptics& o, const NamedPose& pose, const ChainRenderSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  PoseRig rig = makeRig(o, pose, s);
  DisplayModel dm = makeDisplayModel(o.display, o.layout, flatEia(o.layout, {1, 0, 0}), "(flat patch)",
                                     MlaKind::Real, 0.0, relativeEmitter(s));
  std::array<Image, 3> cameraImg, xyzImg;
  for (int c = 0; c < 3; ++c) {
    Vec3d drive(0.0);
    drive[c] = 1.0;
    const PanelEmitter panel(o.display.panel, o.layout, flatEia(o.layout, drive), "(flat patch)", dm.gapMm,
                             relativeEmitter(s));
    cameraImg[size_t(c)] = renderView(*rig.camera, o.camera.sensor, *dm.mla, panel, dm.area, quietView(s)).image;
    xyzImg[size_t(c)] = renderView(*rig.camera, rig.observer, *dm.mla, panel, dm.area, quietView(s)).image;
  }
  PoseResponse r;
  r.pose = pose;
  const PixelMask display = displayMask(*rig.camera, dm.area);
  r.displayPixels = display.count();
  r.measured = interiorOf(display, s.interiorFraction);
  std::vector<float> whiteY(display.on.size(), 0.0f);
  for (size_t i = 0; i < whiteY.size(); ++i)
    for (const Image& im : xyzImg) whiteY[i] += im.data[i * size_t(im.numChannels()) + 1];
  trimByLuminance(r.measured, whiteY, s.trimPercent);
  r.pixels = r.measured.count();
  if (r.pixels < 100)
    throw InputError("", "pose", pose.pose.describe(),
                     "a pose from which the camera sees the display (" + std::to_string(r.pixels) +
                         " interior pixels seen; at least 100 are needed to measure a patch)");
  const Vec3d white = d65WhiteXyz();
  for (int c = 0; c < 3; ++c) {
    r.cameraPerDrive[c] = meanOver(cameraImg[size_t(c)], r.measured);
    r.xyzPerDrive[c] = meanOver(xyzImg[size_t(c)], r.measured) * white;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

FlatPatchMeasurement renderFlatPatch(const ChainOptics& o, const NamedPose& pose, const Vec3d& drive,
                                     const PixelMask& pixels, const ChainRenderSettings& s) {
  PoseRig rig = makeRig(o, pose, s);
  DisplayModel dm = makeDisplayModel(o.display, o.layout, flatEia(o.layout, drive), "(flat patch)", MlaKind::Real,
                                     0.0, relativeEmitter(s));
  FlatPatchMeasurement m;
  m.cameraRgb = meanOver(renderView(*rig.camera, o.camera.sensor, *dm.mla, *dm.panel, dm.area, quietView(s)).image,
                         pixels);
  m.xyz = meanOver(renderView(*rig.camera, rig.observer, *dm.mla, *dm.panel, dm.area, quietView(s)).image, pixels) *
          d65WhiteXyz();
  return m;
}

}  // namespace inim
