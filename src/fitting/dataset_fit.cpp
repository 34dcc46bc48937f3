#include "fitting/dataset_fit.h"

#include <fstream>
#include <algorithm>
#include <nlohmann/json.hpp>

#include "analysis/metrics.h"
#include "core/error.h"
#include "core/json_config.h"
#include "radiance/volume_renderer.h"

namespace inim {

TrainingRays datasetRays(const Dataset& data, const std::vector<int>& frames) {
  TrainingRays r;
  size_t n = 0;
  for (int i : frames) n += size_t(data.frames[size_t(i)].image.width) * size_t(data.frames[size_t(i)].image.height);
  r.origin.reserve(n), r.dir.reserve(n), r.rgb.reserve(n), r.tNear.reserve(n), r.tFar.reserve(n);
  for (int i : frames) {
    const DatasetFrame& f = data.frames[size_t(i)];
    const Image& img = f.image;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        glm::dvec3 o, d;
        frameRay(f, x + 0.5, y + 0.5, o, d);
        r.origin.push_back(Point3(o));
        r.dir.push_back(Vec3(glm::normalize(d)));
        r.rgb.push_back(Vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)));
        r.tNear.push_back(float(data.nearPlane));
        r.tFar.push_back(float(data.farPlane));
      }
  }
  return r;
}

Image renderFrame(const VolumeRenderer& renderer, const Dataset& data, const DatasetFrame& f) {
  const int w = f.image.width, h = f.image.height;
  std::vector<RenderRay> rays(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::dvec3 o, d;
      frameRay(f, x + 0.5, y + 0.5, o, d);
      RenderRay& r = rays[size_t(y) * size_t(w) + size_t(x)];
      r.o = Point3(o), r.d = Vec3(glm::normalize(d));
      r.tNear = float(data.nearPlane), r.tFar = float(data.farPlane);
    }
  std::vector<RadianceSample> out(rays.size());
  renderer.render(rays, out);
  Image img(w, h, {"R", "G", "B"});
  for (size_t p = 0; p < out.size(); ++p)
    for (int c = 0; c < 3; ++c) img.data[p * 3 + size_t(c)] = std::clamp(out[p].rgb[c], 0.0f, 1.0f);
  return img;
}

std::vector<ViewScore> evaluate(const VoxelGrid& grid, const Dataset& data, const std::vector<int>& frames,
                                std::vector<Image>* renders) {
  VolumeRenderer renderer(grid);
  std::vector<ViewScore> scores;
  for (int i : frames) {
    const DatasetFrame& f = data.frames[size_t(i)];
    Image img = renderFrame(renderer, data, f);
    Image truth = colorImage(f.image);
    ViewScore s;
    s.frame = i;
    s.image = f.imagePath;
    s.psnr = psnr(img, truth);
    s.ssim = ssim(img, truth).value;
    scores.push_back(s);
    if (renders) renders->push_back(std::move(img));
  }
  return scores;
}

std::string modelMetadata(const Dataset& data) {
  nlohmann::json j = {{"dataset", data.file}, {"format", data.format}, {"units", "dataset"}};
  // An inim capture records its scene and units in transforms.json (read once already, so
  // a failure here means the file changed since: the metadata then says less).
  if (data.format != "middlebury") {
    nlohmann::json t;
    try {
      t = readJsonFile(data.file);
    } catch (const InputError&) {
    }
    if (t.is_object() && t.contains("inim_capture") && t["inim_capture"].is_object()) {
      const auto& c = t["inim_capture"];
      if (c.value("units", "") == "mm") j["units"] = "mm";
      if (c.contains("scene")) j["scene"] = c["scene"];
    }
  }
  return j.dump();
}

Placement defaultPlacementFor(const std::string& metadata) {
  Placement p;
  p.source = "the model's default";
  p.scaleKey = "scale";
  nlohmann::json j;
  try {
    j = parseJsonText(metadata, "the model's metadata");
  } catch (const InputError&) {  // not ours: no units
  }
  const bool mm = j.is_object() && j.value("units", "") == "mm";
  if (!mm) p.scale = Vec3d(1.0 / 0.0075);  // the paper's NeRF placement: 0.0075 field units per mm
  return p;
}

}  // namespace inim
