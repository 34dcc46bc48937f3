#include "capture/capture.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "capture/capture_poses.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/progress.h"
#include "core/rng.h"
#include "camera/fov_camera.h"
#include "field_render/renderer.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

void check(bool ok, const std::string& key, const std::string& value, const std::string& expected) {
  if (!ok) throw InputError("", key, value, expected);
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// 8-bit PNG of straight (unassociated) RGBA or RGB: OIIO must not un-premultiply it.
void writePng8(const std::string& path, int w, int h, int channels, const std::vector<float>& v) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error("cannot create PNG writer for " + path + ": " + OIIO::geterror());
  OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT8);
  if (channels == 4) {
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  std::vector<unsigned char> bytes(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    float x = std::isfinite(v[i]) ? std::clamp(v[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<unsigned char>(std::lround(x * 255.0f));
  }
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) || !out->close())
    throw std::runtime_error("cannot write " + path + ": " + out->geterror());
}

// The render (linear, R G B A Z) as PNG values: sRGB straight colour (+ alpha).
std::vector<float> pngValues(const Image& render, bool alpha) {
  const int W = render.width, H = render.height, C = alpha ? 4 : 3;
  Image straight(W, H, {"R", "G", "B"});
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      float a = render.at(x, y, 3);
      float scale = !alpha ? 1.0f : (a > 1e-6f ? 1.0f / std::min(a, 1.0f) : 0.0f);
      for (int c = 0; c < 3; ++c) straight.at(x, y, c) = render.at(x, y, c) * scale;
    }
  Image srgb = encodeSRGB(straight);
  std::vector<float> v(size_t(W) * H * C);
  for (size_t p = 0; p < size_t(W) * H; ++p) {
    for (int c = 0; c < 3; ++c) v[p * C + c] = srgb.data[p * 3 + c];
    if (alpha) v[p * C + 3] = std::clamp(render.data[p * 5 + 3], 0.0f, 1.0f);
  }
  return v;
}

nlohmann::json matrixRows(const glm::dmat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return rows;
}

void checkSettings(const CaptureSettings& s) {
  check(s.views > 0, "views", std::to_string(s.views), "at least 1 view");
  check(s.views <= 9999, "views", std::to_string(s.views), "at most 9999 views (frame_NNNN.png)");
  check(s.width > 0, "width", std::to_string(s.width), "a positive image width in pixels");
  check(s.height > 0, "height", std::to_string(s.height), "a positive image height in pixels");
  check(s.hfovDeg > 0 && s.hfovDeg < 179, "hfov_deg", num(s.hfovDeg), "a horizontal field of view in (0, 179) degrees");
  check(s.minElevationDeg >= -90 && s.maxElevationDeg <= 90 && s.minElevationDeg <= s.maxElevationDeg,
        "elevation_deg", num(s.minElevationDeg) + ".." + num(s.maxElevationDeg),
        "-90 <= min <= max <= 90 degrees above the display plane");
  check(s.spp > 0, "spp", std::to_string(s.spp), "at least 1 sample per pixel");
  check(!s.radiusMm || (*s.radiusMm > 0 && std::isfinite(*s.radiusMm)), "radius_mm",
        s.radiusMm ? num(*s.radiusMm) : "", "a positive camera distance in mm");
}

// What the views look at (res.target), how far away (res.radiusMm), and the pinhole intrinsics.
void frameTarget(const Field& scene, const CaptureSettings& s, CaptureResult& res) {
  if (s.target) {
    res.target = *s.target;
  } else {
    Point3 lo, hi;
    scene.bounds(lo, hi);
    res.target = {glm::dvec3(lo), glm::dvec3(hi)};
  }
  const Box3d& t = res.target;
  check(std::isfinite(t.lo.x + t.lo.y + t.lo.z + t.hi.x + t.hi.y + t.hi.z) && t.hi.x >= t.lo.x &&
            t.hi.y >= t.lo.y && t.hi.z >= t.lo.z,
        "target", "(" + num(t.lo.x) + ", " + num(t.lo.y) + ", " + num(t.lo.z) + ")..(" + num(t.hi.x) + ", " +
                      num(t.hi.y) + ", " + num(t.hi.z) + ")",
        "a finite box with lo <= hi");
  const glm::dvec3 half = 0.5 * t.extent();
  const double tanX = std::tan(0.5 * s.hfovDeg * M_PI / 180.0), tanY = tanX * s.height / s.width;
  if (s.radiusMm) {
    res.radiusMm = *s.radiusMm;
  } else {
    // Frame the target's front view: its x-y extent fits the image at the target's front face.
    res.radiusMm = half.z + std::max(half.x / tanX, half.y / tanY);
    if (!(res.radiusMm > 0)) res.radiusMm = 100.0;  // an empty (point) target: any distance frames it
  }

  Intrinsics& K = res.intrinsics;
  K.width = s.width;
  K.height = s.height;
  K.fx = K.fy = 0.5 * s.width / tanX;  // square pixels: FovCameraModel's tanHalfY = tanX * H / W
  K.cx = 0.5 * s.width;
  K.cy = 0.5 * s.height;
}

// transforms.json (instant-ngp / nerfstudio): the shared intrinsics, the frames and how they were made.
nlohmann::json transformsJson(const CaptureSettings& s, const CaptureResult& res, nlohmann::json frames) {
  const Intrinsics& K = res.intrinsics;
  const Box3d& t = res.target;
  nlohmann::json j;
  j["camera_model"] = "OPENCV";
  j["fl_x"] = K.fx;
  j["fl_y"] = K.fy;
  j["cx"] = K.cx;
  j["cy"] = K.cy;
  j["w"] = K.width;
  j["h"] = K.height;
  j["k1"] = j["k2"] = j["p1"] = j["p2"] = 0.0;
  j["frames"] = std::move(frames);
  j["inim_capture"] = {
      {"scene", s.sceneFile},
      {"units", "mm"},
      {"_note", "poses are in the scene's own frame and units (display frame: x right, y up, z toward "
                "the viewer, MLA plane z = 0); scene-to-dataset transform = identity"},
      {"target_mm", {{t.lo.x, t.lo.y, t.lo.z}, {t.hi.x, t.hi.y, t.hi.z}}},
      {"radius_mm", res.radiusMm},
      {"elevation_deg", {s.minElevationDeg, s.maxElevationDeg}},
      {"hfov_deg", s.hfovDeg},
      {"spp", s.spp},
      {"seed", s.seed},
      {"alpha", s.writeAlpha}};
  return j;
}

}  // namespace

CaptureResult captureScene(const Field& scene, const CaptureSettings& s, const std::string& outDir) {
  checkSettings(s);
  CaptureResult res;
  frameTarget(scene, s, res);
  const glm::dvec3 centre = res.target.center();

  auto t0 = std::chrono::steady_clock::now();
  OutputSet outputs;
  nlohmann::json frames = nlohmann::json::array();
  ProgressBar bar("capture", uint64_t(s.views), s.progress && ProgressBar::stderrIsTerminal());
  const std::vector<glm::dvec3> dirs = capDirections(s.views, s.minElevationDeg, s.maxElevationDeg);
  for (int i = 0; i < s.views; ++i) {
    FovCameraSettings cs;
    cs.width = s.width;
    cs.height = s.height;
    cs.hfovDeg = float(s.hfovDeg);
    cs.pose.eye = roundedToFloat(centre + res.radiusMm * dirs[i]);
    cs.pose.lookAt = roundedToFloat(centre);
    // The pose as the camera will build it, from the same float eye/look-at.
    glm::dmat4 c2w = lookAtCameraToWorld(cs.pose.eye, cs.pose.lookAt);
    cs.pose.up = glm::dvec3(c2w[1]);  // == +y unless the fallback applied; keeps them in sync
    FovCameraModel camera(cs);
    RenderSettings rs;
    rs.spp = s.spp;
    rs.seed = hashCombine(s.seed, uint64_t(i));
    rs.progress = false;
    RenderResult r = renderField(scene, camera, rs);
    res.raysTraced += r.raysTraced;

    char name[32];
    std::snprintf(name, sizeof name, "images/frame_%04d.png", i + 1);
    std::string finalPath = (fs::path(outDir) / name).string();
    writePng8(outputs.add(finalPath), s.width, s.height, s.writeAlpha ? 4 : 3, pngValues(r.image, s.writeAlpha));

    CaptureView v;
    v.imagePath = finalPath;
    v.cameraToWorld = c2w;
    if (s.keepDepth) {
      v.depth = Image(s.width, s.height, {"Z"});
      for (size_t p = 0; p < size_t(s.width) * s.height; ++p) v.depth.data[p] = r.image.data[p * 5 + 4];
    }
    res.views.push_back(std::move(v));
    frames.push_back({{"file_path", name}, {"transform_matrix", matrixRows(c2w)}});
    bar.add(1);
  }
  bar.finish();

  res.transformsPath = (fs::path(outDir) / "transforms.json").string();
  {
    std::string tmp = outputs.add(res.transformsPath);
    std::ofstream out(tmp);
    out << transformsJson(s, res, std::move(frames)).dump(2) << "\n";
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  outputs.commit();
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace inim
