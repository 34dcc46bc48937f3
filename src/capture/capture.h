#pragma once
// A synthetic posed capture of a Field, like a smartphone scan: views from a cap of camera
// positions in front of the scene, written as a Nerfstudio-style transforms.json plus sRGB
// PNGs, which loadDataset (dataset/dataset.h) and NeRF tools read back.
//
//   auto scene = AnalyticScene::load("scenes/paper-fig7.json");
//   CaptureSettings s;  s.sceneFile = scene->file();
//   CaptureResult r = captureScene(*scene, s, "out/capture");
//
// Where the cameras go, and why. The display (docs/design.md) sits in the scene's frame: x right,
// y up, z toward the viewer, the MLA at z = 0. It only ever sends light toward +z, within its
// viewing angle (about +-7 to 9 degrees for the prototype), and the orthoscopic query asks the
// field for rays from the viewer's side going toward -z. A capture for display should
// therefore see the scene from the viewer's side, densely around the +z axis, with enough
// spread for a NeRF to triangulate depth. So the "hemisphere" is a cap around +z (elevation
// above the display plane, default 50..90 degrees = up to 40 degrees off the axis), cameras
// look at the target's centre with +y up, as someone walking around a tabletop in front of
// the display would hold a phone. Views from behind (z < 0) are useless for the display and
// are never generated; views near grazing (low elevation) see mostly the scene's sides.
//
// Units: the scene's own (mm); poses are written in the scene frame, so the scene-to-dataset
// transform is the identity. The json records this as "inim_capture": {"scene": ...,
// "units": "mm", ...} so later steps (placement of a trained field) need no rescaling.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "dataset/dataset.h"
#include "field/field.h"

namespace inim {

struct CaptureSettings {
  int views = 64;
  int width = 400, height = 300;
  double hfovDeg = 40.0;            // horizontal field of view (pinhole)
  double minElevationDeg = 50.0;    // above the display plane (xy), toward +z
  double maxElevationDeg = 90.0;
  // What the views look at and frame. Default: the field's bounds.
  std::optional<Box3d> target;
  // Camera distance from the target centre. Default: the distance at which the target's
  // x-y extent (seen along -z) fits the field of view, plus its front half-depth.
  std::optional<double> radiusMm;
  int spp = 16;
  uint64_t seed = 1;
  std::string sceneFile;   // recorded in the json ("inim_capture.scene")
  bool writeAlpha = true;  // RGBA PNG (alpha = opacity), colour un-premultiplied; see below
  bool keepDepth = false;  // keep each view's depth (distance along the ray, mm) in the result
  bool progress = true;    // a bar on a terminal only
};

struct CaptureView {
  std::string imagePath;     // final path of the PNG
  glm::dmat4 cameraToWorld;  // OpenGL axes, scene frame (mm)
  Image depth;               // channel Z (0 where A = 0) when keepDepth, else empty
};

struct CaptureResult {
  std::string transformsPath;
  Intrinsics intrinsics;     // shared by all views
  Box3d target;
  double radiusMm = 0;
  std::vector<CaptureView> views;
  double seconds = 0;
  uint64_t raysTraced = 0;
};

// Renders the views and writes outDir/transforms.json and outDir/images/frame_NNNN.png
// (1-based, 4 digits), all through an OutputSet: nothing is left behind on failure.
//
// PNG colour: the renderer's RGB is the pixel's mean radiance, and A its coverage. With
// writeAlpha, the PNG stores straight colour RGB/A (sRGB-encoded) and alpha A, so a loader
// compositing c*a + bg*(1-a) gets the render back exactly where the environment is black;
// a non-black environment (paper-fig7's dim "sky") is then kept only inside partly covered
// pixels. Without writeAlpha, the PNG is RGB as rendered, environment included.
// Throws InputError for bad settings (naming the setting).
CaptureResult captureScene(const Field& scene, const CaptureSettings& settings, const std::string& outDir);

}  // namespace inim
