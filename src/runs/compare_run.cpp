#include "runs/compare_run.h"

#include <memory>

#include "core/file_kinds.h"
#include "core/error.h"
#include "core/format.h"
#include "core/image.h"
#include "core/output_file.h"
#include "spectral/color.h"

namespace inim {

namespace {

// InputError naming `space` when the colour configuration has no such space.
void checkSpace(const std::string& space) {
  try {
    ColorSystem::instance().convert(Vec3(0.0f), space, "cie_xyz_d65");
  } catch (const InputError& e) {
    throw InputError("", "space", space, e.expected());
  }
}

}  // namespace

CompareRunResult runCompare(const CompareRunSettings& s) {
  CompareRunResult r;
  CompareOptions& co = r.options;
  co = s.options;
  co.spaceA = s.space.empty() ? defaultColorSpaceForFile(s.a) : s.space;
  co.spaceB = s.space.empty() ? defaultColorSpaceForFile(s.b) : s.space;
  if (!s.space.empty()) checkSpace(s.space);
  if (!s.deMap.empty() && !isFileKind(s.deMap, FileKind::Exr))
    throw InputError("", "de_map", s.deMap, "an .exr file (the map holds unbounded float values)");
  const Image a = readImage(s.a), b = readImage(s.b);  // InputError for NaN / Inf
  requireSameSize(a, b, s.a, s.b);
  std::unique_ptr<PixelMask> mask;
  if (!s.mask.empty()) {
    mask = std::make_unique<PixelMask>(loadMask(s.mask));
    requireMaskFits(*mask, a.width, a.height);
  }
  r.metrics = compareImages(a, b, co, mask.get(), s.a, s.b);
  if (!s.deMap.empty()) {
    OutputSet out;
    const std::string tmp = out.add(s.deMap);
    Image map(a.width, a.height, {"Y"});
    map.data = deltaE2000Map(a, b, co.spaceA, co.spaceB, co.whiteLuminance);
    writeImage(map, tmp);
    out.commit();
  }
  return r;
}

std::string compareJson(const CompareRunSettings& s, const CompareRunResult& r) {
  const CompareOptions& co = r.options;
  Json j = metricsJson(r.metrics);
  j["a"] = s.a;
  j["b"] = s.b;
  j["mask"] = s.mask.empty() ? Json(nullptr) : Json(s.mask);
  j["space_a"] = co.spaceA;
  j["space_b"] = co.spaceB;
  j["values"] = metricValuesName(co.values);
  j["peak"] = co.peak;
  j["ssim_channels"] = ssimChannelsName(co.ssimChannels);
  j["white_luminance"] = co.whiteLuminance;
  return j.dump(2) + "\n";
}

std::string compareText(const CompareRunSettings& s, const CompareRunResult& r) {
  std::string text = "A            " + s.a + "\nB            " + s.b + "\n";
  if (!s.mask.empty()) text += "mask         " + s.mask + "\n";
  return text + metricsText(r.metrics, r.options);
}

}  // namespace inim
