#include "runs/fig11_depth.h"

#include "analysis/metrics.h"
#include "core/format.h"
#include "display/display_info.h"
#include "display/ei_layout.h"

namespace inim {

ReferenceDepth takeDepthChannels(Image& reference) {
  ReferenceDepth d;
  const int zc = reference.channelIndex("Z"), ac = reference.channelIndex("A"), sc = reference.channelIndex("dZ");
  if (zc < 0) return d;
  d.present = true;
  d.width = reference.width, d.height = reference.height;
  const size_t n = size_t(reference.width) * size_t(reference.height);
  d.z.resize(n);
  d.coverage.assign(n, 1.0f);  // without A every pixel counts as covered
  if (sc >= 0) d.spread.resize(n);
  std::vector<std::string> keep;
  std::vector<int> from;
  for (int c = 0; c < reference.numChannels(); ++c)
    if (c != zc && c != ac && c != sc) keep.push_back(reference.channels[size_t(c)]), from.push_back(c);
  Image rest(reference.width, reference.height, keep);
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const size_t i = size_t(y) * size_t(reference.width) + size_t(x);
      d.z[i] = reference.at(x, y, zc);
      if (ac >= 0) d.coverage[i] = reference.at(x, y, ac);
      if (sc >= 0) d.spread[i] = reference.at(x, y, sc);
      for (size_t k = 0; k < from.size(); ++k) rest.at(x, y, int(k)) = reference.at(x, y, from[k]);
    }
  reference = std::move(rest);
  return d;
}

DepthMarks depthMarksFor(const Display& display) {
  const GapInfo rec = derive(display).reconstruction;
  DepthMarks m;
  if (rec.opticalReferencePlaneMm) {
    m.referencePlaneMm = rec.opticalReferencePlaneMm;
    m.referencePlaneLabel = "L = " + formatNumber(*m.referencePlaneMm, "%.1f") + " mm (through the cover glass)";
  } else if (rec.referencePlaneMm) {
    m.referencePlaneMm = rec.referencePlaneMm;
    m.referencePlaneLabel = "L = " + formatNumber(*m.referencePlaneMm, "%.1f") + " mm";
  }
  m.samplingRangeMm = rec.depthRangeMm;
  m.samplingRangeLabel = "depth range |z| ≤ " + formatNumber(rec.depthRangeMm, "%.3g") + " mm (lateral sampling ≤ 2P)";
  if (m.referencePlaneMm && *m.referencePlaneMm > 0.0) {
    // The facets of neighbouring lenslets drift apart by P |z - L| / L; within half a magnified
    // pixel (d L / g) of each other the pixel quantisation hides it (validation/depth-sharpness).
    const double L = *m.referencePlaneMm, g = rec.opticalGapMm.value_or(rec.gapMm);
    const double half = 0.5 * (display.panel.pixelPitchMm * L / g) * L / computeLayout(display).lensPitchMm;
    m.depthOfFieldMm = std::pair{L - half, L + half};
    m.depthOfFieldLabel = "depth of field |z − L| ≤ ½ (d L/g) L/P = " + formatNumber(half, "%.2g") + " mm";
  }
  return m;
}

std::vector<DepthBin> Fig11DepthError::addPose(const std::string& name, const std::string& label,
                                               const Fig11PoseImages& img, const ReferenceDepth& depth,
                                               const PixelMask& mask, const std::vector<float>& deltaE,
                                               Json& poseMetrics) {
  if (!depth.present) return {};
  std::vector<DepthBin> bins =
      errorVsDepth(img.refLinear, img.recLinear, depth, &mask, {}, &deltaE);
  poseMetrics["depth_error"] = depthBinsJson(bins);
  writeCsv(out("depth_error_" + name + ".csv"), depthBinsCsvHeader(), depthBinsCsvRows(bins));
  Image planes(depth.width, depth.height, {"A", "Z", "dZ"});
  for (size_t i = 0; i < depth.z.size(); ++i) {
    planes.data[3 * i] = depth.coverage[i];
    planes.data[3 * i + 1] = depth.z[i];
    planes.data[3 * i + 2] = depth.spread.empty() ? 0.0f : depth.spread[i];
  }
  writeImage(planes, out("reference_" + name + "_depth.exr"));
  curves_.push_back({label, bins});
  return bins;
}

void Fig11DepthError::writeFigure(const Display& display) {
  if (curves_.empty()) return;
  writeImage(depthErrorFigure(curves_, depthMarksFor(display), "Fig. 11 error against depth"),
             out("depth_error.png"));
}

}  // namespace inim
