#include "dataset/dataset.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>

#include "core/error.h"
#include "core/format.h"
#include "dataset/dataset_image.h"
#include "dataset/middlebury.h"
#include "dataset/scene_box.h"
#include "dataset/transforms_json.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), ::tolower);
  return s;
}

// The dataset file for `path`: itself if a file; in a folder transforms.json, then
// transforms_train.json, then the single *_par.txt.
std::string datasetFile(const std::string& path) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return path;
  if (!fs::is_directory(path, ec))
    throw InputError(path, "dataset", path, "a dataset folder, transforms*.json or *_par.txt");
  for (const char* name : {"transforms.json", "transforms_train.json"}) {
    fs::path p = fs::path(path) / name;
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  std::vector<std::string> pars;
  for (const auto& entry : fs::directory_iterator(path, ec)) {
    std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name.size() > 8 && name.substr(name.size() - 8) == "_par.txt")
      pars.push_back(entry.path().string());
  }
  std::sort(pars.begin(), pars.end());
  if (pars.size() == 1) return pars[0];
  if (pars.size() > 1)
    throw InputError(path, "dataset", pars[0] + ", " + pars[1] + ", ...",
                     "a folder with one *_par.txt (name the file to choose)");
  throw InputError(path, "dataset", "no transforms.json, transforms_train.json or *_par.txt",
                   "a dataset folder (Blender/Nerfstudio/instant-ngp or Middlebury)");
}

// The image a frame names: as written, else with a known extension appended (Blender writes
// "./train/r_0"). Empty if none exists.
std::string resolveImage(const fs::path& folder, const std::string& filePath) {
  fs::path p = folder / filePath;
  std::error_code ec;
  if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  for (const char* ext : {".png", ".jpg", ".jpeg", ".exr", ".tif", ".tiff", ".PNG", ".JPG", ".JPEG", ".EXR"}) {
    fs::path q = p;
    q += ext;
    if (fs::is_regular_file(q, ec)) return q.lexically_normal().string();
  }
  return "";
}

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// Focal lengths > 0 and finite, the principal point inside the image or less than half an image
// beyond it: a cx of 1e30 once trained a model of black images to "PSNR inf dB" with exit 0.
void checkIntrinsics(const DatasetManifest& man, const FrameSpec& s, const Intrinsics& k) {
  const std::string suffix = ".file_path";
  std::string frame = s.key;
  if (frame.size() > suffix.size() && frame.compare(frame.size() - suffix.size(), suffix.size(), suffix) == 0)
    frame.resize(frame.size() - suffix.size());
  auto fail = [&](const std::string& key, double v, const std::string& expected) {
    throw InputError(man.file, key + " (" + frame + ")", formatNumber(v), expected);
  };
  for (auto [key, f] : {std::pair{"fl_x", k.fx}, {"fl_y", k.fy}})
    if (!(f > 0.0 && std::isfinite(f))) fail(key, f, "a focal length > 0 pixels");
  for (auto [key, c, n] : {std::tuple{"cx", k.cx, k.width}, {"cy", k.cy, k.height}})
    if (!(c >= -0.5 * n && c <= 1.5 * n))
      fail(key, c, "a principal point inside the " + sizeText(k.width, k.height) + " image or less than half an image beyond it (" +
                       formatNumber(-0.5 * n) + " to " + formatNumber(1.5 * n) + " px)");
}

// Completes a frame's intrinsics from its image size and checks they agree.
Intrinsics completeIntrinsics(const DatasetManifest& man, const FrameSpec& s, const std::string& image,
                              int imgW, int imgH) {
  Intrinsics k = s.intrinsics;
  if ((k.width > 0 && k.width != imgW) || (k.height > 0 && k.height != imgH))
    throw InputError(man.file, s.key + " (w, h)", sizeText(k.width, k.height),
                     "the size of its image " + image + ", which is " + sizeText(imgW, imgH));
  k.width = imgW;
  k.height = imgH;
  if (k.fx <= 0) {
    k.fx = 0.5 * imgW / std::tan(0.5 * s.angleX);
    k.fy = s.angleY > 0 ? 0.5 * imgH / std::tan(0.5 * s.angleY) : k.fx;
  }
  if (std::isnan(k.cx)) k.cx = 0.5 * imgW;
  if (std::isnan(k.cy)) k.cy = 0.5 * imgH;
  checkIntrinsics(man, s, k);
  return k;
}

}  // namespace

void splitTrainTest(int count, int holdoutEvery, std::vector<int>& train, std::vector<int>& test) {
  train.clear();
  test.clear();
  for (int i = 0; i < count; ++i)
    (holdoutEvery > 0 && i % holdoutEvery == 0 ? test : train).push_back(i);
}

Dataset loadDataset(const std::string& path, const DatasetOptions& opt) {
  if (opt.downscale < 1)
    throw InputError(path, "downscale", std::to_string(opt.downscale), "an integer factor >= 1");
  if (opt.holdoutEvery < 0)
    throw InputError(path, "holdout_every", std::to_string(opt.holdoutEvery), "an integer >= 0 (0 = no test frames)");
  const std::string file = datasetFile(path);
  const bool isPar = lower(file).size() > 8 && lower(file).substr(file.size() - 8) == "_par.txt";
  DatasetManifest man = isPar ? readMiddleburyPar(file) : readTransformsJson(file);
  const fs::path folder = fs::path(file).parent_path();

  // Resolve images; frames without one are skipped (real captures list more than they keep).
  std::vector<int> kept;
  std::vector<std::string> images;
  std::string firstMissing;
  for (size_t i = 0; i < man.frames.size(); ++i) {
    std::string img = resolveImage(folder, man.frames[i].filePath);
    if (img.empty()) {
      if (firstMissing.empty()) firstMissing = man.frames[i].filePath;
      continue;
    }
    kept.push_back(int(i));
    images.push_back(img);
  }
  Dataset d;
  d.file = file;
  d.format = man.format;
  d.background = opt.background;
  d.ngpBox = man.ngpBox;
  d.skippedFrames = int(man.frames.size() - kept.size());
  if (kept.empty())
    throw InputError(file, "frames", std::to_string(man.frames.size()) + " frames, none with an existing image" +
                                         (firstMissing.empty() ? "" : " (first: " + firstMissing + ")"),
                     "at least one frame whose image file exists");
  if (d.skippedFrames > 0)
    std::cerr << "inim: warning: " << file << ": skipped " << d.skippedFrames << " of " << man.frames.size()
              << " frames whose images are missing (first: " << firstMissing << ")\n";

  // Load in parallel; the first error by frame order is reported, whatever the thread timing.
  d.frames.resize(kept.size());
  std::vector<std::exception_ptr> errors(kept.size());
  tbb::parallel_for(size_t(0), kept.size(), [&](size_t i) {
    try {
      const FrameSpec& s = man.frames[kept[i]];
      DatasetFrame& f = d.frames[i];
      f.imagePath = images[i];
      f.sourceIndex = kept[i];
      f.cameraToWorld = s.cameraToWorld;
      ImageHeader h = readImageHeader(images[i]);
      Intrinsics full = completeIntrinsics(man, s, images[i], h.width, h.height);
      f.hadAlpha = h.hasAlpha;
      int w = downscaledSize(h.width, opt.downscale), hh = downscaledSize(h.height, opt.downscale);
      f.intrinsics = opt.downscale > 1 ? full.resized(w, hh) : full;
      if (opt.loadImages) f.image = readDatasetImage(images[i], opt.background, opt.downscale, &f.hadAlpha);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);

  splitTrainTest(int(d.frames.size()), opt.holdoutEvery, d.train, d.test);
  SceneBoxEstimate est = estimateSceneBox(d.frames);
  d.sceneBox = opt.sceneBox ? *opt.sceneBox : est.box;
  d.nearPlane = opt.nearPlane ? *opt.nearPlane : est.nearPlane;
  d.farPlane = opt.farPlane ? *opt.farPlane : est.farPlane;
  if (!(d.nearPlane > 0 && d.farPlane > d.nearPlane))
    throw InputError(file, "near/far", std::to_string(d.nearPlane) + "/" + std::to_string(d.farPlane),
                     "0 < near < far");
  return d;
}

void frameRay(const DatasetFrame& f, double px, double py, glm::dvec3& origin, glm::dvec3& dir) {
  glm::dvec2 n = pixelToNormalized(f.intrinsics, {px, py});
  // OpenCV normalised (x right, y down, +z forward) -> OpenGL camera (y up, looks down -z).
  glm::dvec3 dCam(n.x, -n.y, -1.0);
  origin = glm::dvec3(f.cameraToWorld[3]);
  dir = glm::normalize(glm::dmat3(f.cameraToWorld) * dCam);
}

bool projectToFrame(const DatasetFrame& f, const glm::dvec3& world, glm::dvec2& pixel) {
  glm::dvec3 c = glm::dvec3(glm::inverse(f.cameraToWorld) * glm::dvec4(world, 1.0));
  if (!(c.z < 0.0)) return false;
  pixel = normalizedToPixel(f.intrinsics, {c.x / -c.z, -c.y / -c.z});
  return true;
}

}  // namespace inim
