#pragma once
// Where in depth a reconstruction is wrong: the error of a reconstruction against its reference,
// binned by the depth of the scene surface each pixel sees (the reference's Z channel,
// display_view/reference_renderer.h), and a figure of it with the planes that explain it marked.
//
// A pixel counts when the mask says so, its coverage (the reference's A channel) is >= 0.5 (it
// sees a surface rather than a mix of surface and background) and the surfaces its rays hit lie
// within one bin's width in z (the dZ channel): a pixel on an edge between a near and a far
// surface has a mean z where neither is, and would put their error in a bin between them. Such
// mixed pixels are counted in the bin of their mean z but left out of its metrics. Bins are
// equal slices of z; per bin:
//   relative RMSE  sqrt(mean |rec - ref|^2) / sqrt(mean |ref|^2), |.| over R, G, B, on the
//                  images as given (fig11: linear camera RGB, exposed alike);
//   error / detail sqrt(mean |rec - ref|^2) / sqrt(mean |ref - mean ref|^2): the error against
//                  the detail there is to show in the bin (the reference's RMS about the bin's
//                  mean colour). It compares depths that hold different content: a blurred
//                  smooth backdrop has a small relative RMSE but the same error / detail as a
//                  blurred texture. 1 = as far off as the bin's mean colour painted flat;
//   mean CIEDE2000 of a per-pixel map (deltaE2000Map of the encoded images, as compareImages
//                  uses; without one, of the two images taken as linear Rec.709).
// A bin with fewer than `minPixels` pixels keeps its count but has NaN metrics (too few to say).
//
//   DepthBinning b;                                // 24 bins over the 1st..99th percentile of z
//   std::vector<float> de = deltaE2000Map(refSrgb, recSrgb, "srgb", "srgb");
//   auto bins = errorVsDepth(ref, rec, {z, a, dz}, &mask, b, &de);
//   writePlot(depthErrorPlot({{"0°", bins}}, marks, DepthErrorQuantity::RelativeRmse), "e.png");
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/plot.h"
#include "core/image.h"
#include "core/json_config.h"
#include "core/pixel_mask.h"

namespace inim {

// A reference's depth per pixel (display_view/reference_renderer.h, channels A, Z and dZ): width x
// height, row-major.
struct DepthMap {
  std::vector<float> z;         // mean display-frame z of the surfaces the pixel's rays hit, mm
  std::vector<float> coverage;  // the fraction of its rays that hit a surface
  std::vector<float> spread;    // max - min of those surfaces' z, mm; empty: unknown (taken as 0)
};

struct DepthBinning {
  // The z range binned, mm; default: the 1st and 99th percentiles of the counted pixels' z
  // (pixels outside the range are left out). A range of zero width (a flat scene) is widened
  // to 1 mm about its z.
  std::optional<double> minZ, maxZ;
  int count = 24;             // bins, >= 1
  double minCoverage = 0.5;   // a pixel counts from this coverage (A) up
  int64_t minPixels = 20;     // fewer pixels in a bin: NaN metrics
  bool leaveOutMixed = true;  // pixels whose surfaces spread over more than a bin's width
};

struct DepthBin {
  double zLo = 0.0, zHi = 0.0, zCentre = 0.0;  // mm, display frame
  int64_t pixels = 0;       // the pixels its metrics are over
  int64_t mixedPixels = 0;  // left out: their surfaces spread over more than the bin's width
  double relRmse = 0.0;     // NaN when pixels < minPixels or the reference is black there
  double errorOverDetail = 0.0;  // NaN when pixels < minPixels or the reference is flat there
  double de2000Mean = 0.0;  // NaN when pixels < minPixels
};

// `deltaE`: an optional per-pixel CIEDE2000 map of the images' size (see above). `mask`: null
// for every pixel. Empty when no pixel counts. InputError when sizes disagree or the binning is
// invalid (count < 1, minZ >= maxZ when both given).
std::vector<DepthBin> errorVsDepth(const Image& reference, const Image& reconstruction, const DepthMap& depth,
                                   const PixelMask* mask, const DepthBinning& b = {},
                                   const std::vector<float>* deltaE = nullptr);

// Designs compared depth by depth: each curve's error in each bin over the lowest any curve
// reaches in that bin (RMSE_i / min_j RMSE_j; 1 for the best design at that depth). The curves
// must be of the same reference and mask (the same bins and pixels: a gap sweep of one scene
// seen from one pose), so the ratio cancels what each bin holds: a fine texture at one depth and
// a smooth backdrop at another no longer decide the shape of the curve; only how the designs
// differ there does. NaN where the curve's bin has no metric; where the lowest is 0, 1 for the
// curves at 0 and infinity for the rest. InputError (key depth_bins) when the curves' bins differ.
std::vector<std::vector<double>> errorRelativeToLowest(const std::vector<std::vector<DepthBin>>& curves);

// [{z_lo, z_hi, pixels, mixed_pixels, rel_rmse, de2000_mean, error_over_detail}, ...]; NaN
// metrics as null.
Json depthBinsJson(const std::vector<DepthBin>& bins);
// CSV: z_lo_mm, z_hi_mm, z_centre_mm, pixels, mixed_pixels, rel_rmse, de2000_mean,
// error_over_detail ("nan" where NaN).
std::vector<std::string> depthBinsCsvHeader();
std::vector<std::vector<std::string>> depthBinsCsvRows(const std::vector<DepthBin>& bins);

// ---------------------------------------------------------------------------------------
// The figure

struct DepthErrorCurve {
  std::string name;  // legend entry (a pose: "0°", "H -7°", ...)
  std::vector<DepthBin> bins;
};

// What is marked: the MLA plane z = 0 always; when given, the reference image plane L (where the
// lenslets image the panel; a vertical line), the depth of field around it (shaded orange: the
// depths whose lenslet facets line up within half a magnified pixel) and the depth range
// |z| <= samplingRangeMm around the MLA plane (shaded blue: lateral sampling <= 2P).
struct DepthMarks {
  std::optional<double> referencePlaneMm;
  std::string referencePlaneLabel = "L";
  std::optional<std::pair<double, double>> depthOfFieldMm;  // [near, far] z
  std::string depthOfFieldLabel = "depth of field";
  double samplingRangeMm = 0.0;  // 0: no band
  std::string samplingRangeLabel = "depth range";
};

enum class DepthErrorQuantity { RelativeRmse, ErrorOverDetail, DeltaE2000 };

// One quantity against z (bin centres; NaN bins break the lines), a curve per entry. The x range
// holds every bin and the marked planes; the band is clipped to it. The y axis starts at 0, or
// is logarithmic when the values spread over more than a decade.
Plot depthErrorPlot(const std::vector<DepthErrorCurve>& curves, const DepthMarks& marks, DepthErrorQuantity q);
// Relative RMSE (with the legend), error / detail and mean CIEDE2000, stacked, on the same z range
// with their plot areas lined up (alignPlotAreas): one image (PNG-ready sRGB).
Image depthErrorFigure(const std::vector<DepthErrorCurve>& curves, const DepthMarks& marks,
                       const std::string& title = "Error against depth");

}  // namespace inim
