#pragma once
// `inim compare` as a library: full-reference image metrics of A against B (PSNR, SSIM, and
// the mean, 95th percentile and max of the per-pixel CIEDE2000), optionally within a mask, and
// the CIEDE2000 map as an EXR. Errors name settings (space, de_map) before reading any image.
#include <string>

#include "analysis/metrics.h"

namespace inim {

struct CompareRunSettings {
  std::string a, b;        // the images; B the same size as A
  std::string mask;        // "": every pixel counts
  std::string space;       // both images' colour space; "": per file (defaultColorSpaceForFile)
  std::string deMap;       // "": no map; else an .exr for the per-pixel CIEDE2000
  CompareOptions options;  // its spaces are set from `space`
};

struct CompareRunResult {
  CompareOptions options;  // as used
  ImageMetrics metrics;
};

CompareRunResult runCompare(const CompareRunSettings& s);

// The result as `inim compare` prints it: JSON (the metrics and the settings), or text.
std::string compareJson(const CompareRunSettings& s, const CompareRunResult& r);
std::string compareText(const CompareRunSettings& s, const CompareRunResult& r);

}  // namespace inim
