#pragma once
// Full-reference image metrics: PSNR, SSIM and CIEDE2000, each with an optional mask.
//
// Colour channels. Every metric reads the colour of a pixel as three values: the channels
// named R, G, B if the image has all three; otherwise its first three channels that are not
// alpha ("A"); a single (non-alpha) channel is grey and is repeated three times. Alpha and
// other extra channels are ignored.
//
// Masks. A mask is a single-channel image, or the alpha channel of an image, of the same
// size as the images compared; a pixel counts when its mask value is > 0.5. Pixels that do
// not count have no influence on any metric (for SSIM they are also left out of the local
// statistics of their neighbours, see ssim()).
//
// All functions are deterministic: parallel work (TBB) is reduced per row in a fixed order,
// so results do not depend on the thread count.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/json_config.h"
#include "core/pixel_mask.h"

namespace inim {

// ---------------------------------------------------------------------------------------
// Masks and channels

// From a single-channel image (that channel) or an image with an "A" channel (alpha).
// InputError naming `source` for any other image.
PixelMask maskFromImage(const Image& img, const std::string& source = "mask");
// readImage(path) + maskFromImage.
PixelMask loadMask(const std::string& path);

// The colour of every pixel as interleaved R,G,B floats (see "Colour channels" above).
// InputError naming `name` if the image has no colour channel.
std::vector<float> colorValues(const Image& img, const std::string& name = "image");
// The same as a 3-channel {"R","G","B"} image.
Image colorImage(const Image& img, const std::string& name = "image");

// InputError naming both images when their sizes differ.
void requireSameSize(const Image& a, const Image& b, const std::string& nameA, const std::string& nameB);
// InputError naming the mask's source when it does not match the image size, or when it
// selects no pixel.
void requireMaskFits(const PixelMask& mask, int width, int height);

// ---------------------------------------------------------------------------------------
// PSNR

// Mean squared error over the three colour values of the counted pixels, in the units of
// the values given.
double meanSquaredError(const Image& a, const Image& b, const PixelMask* mask = nullptr);
// PSNR = 10 log10(peak² / MSE) in dB, on the values as given: pass linear values with the
// peak of the linear range, or display-encoded values with peak 1 (what 8-bit PSNR
// conventionally uses; compareImages() does this by default). Values are not clamped.
// Identical images (MSE = 0) give +infinity; JSON reports write it as null.
double psnr(const Image& a, const Image& b, double peak = 1.0, const PixelMask* mask = nullptr);
double psnrFromMse(double mse, double peak);

// ---------------------------------------------------------------------------------------
// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004, "Image quality assessment: from error
// visibility to structural similarity")
//
// Local statistics use an 11x11 circular-symmetric Gaussian window (σ = 1.5, weights
// normalised to sum 1), population (not sample) variances, C1 = (K1 L)², C2 = (K2 L)² with
// K1 = 0.01, K2 = 0.03 and L the dynamic range of the values. As in the authors' reference
// implementation (ssim_index.m, and scikit-image with gaussian_weights=True,
// use_sample_covariance=False), only windows that lie entirely inside the image are used:
// the SSIM map covers pixels [5, W-5) x [5, H-5) and the result is its mean.
//
// With a mask, a window counts when its centre pixel counts, and its statistics are
// weighted by Gaussian × mask (normalised convolution), so pixels outside the mask never
// influence the result. Without a mask this is exactly the standard definition.
enum class SsimChannels {
  Luminance,       // on Y = 0.2126 R + 0.7152 G + 0.0722 B of the values given (luma if encoded)
  PerChannelMean,  // SSIM of R, G and B separately, averaged
};

struct SsimOptions {
  double dynamicRange = 1.0;  // L
  SsimChannels channels = SsimChannels::Luminance;
  int windowSize = 11;  // odd
  double sigma = 1.5;
  double k1 = 0.01, k2 = 0.03;
};

struct SsimResult {
  // Mean SSIM; NaN when no window counts (an image smaller than the window, or a mask that
  // selects no pixel at least windowSize/2 from the border). Check `windows`.
  double value = 0.0;
  int64_t windows = 0;  // number of windows (SSIM-map pixels) averaged
};

SsimResult ssim(const Image& a, const Image& b, const SsimOptions& opt = {}, const PixelMask* mask = nullptr);
// The SSIM of two single-channel planes (row-major, width x height) — the core of ssim().
// `mask` may be null. Returns the sum of the map over the windows counted, and their number.
struct SsimSum {
  double sum = 0.0;
  int64_t windows = 0;
};
SsimSum ssimPlane(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                  const SsimOptions& opt, const PixelMask* mask = nullptr);
// The normalised 1-D Gaussian of the window (size windowSize, standard deviation sigma).
std::vector<double> ssimGaussian(int windowSize, double sigma);

// ---------------------------------------------------------------------------------------
// CIEDE2000

// Per-pixel ΔE2000 between two images whose colour values are linear (or encoded) RGB in the
// given OpenColorIO colour spaces (lin_rec709, srgb, display_p3, acescg, cie_xyz_d65, ...):
// each image goes to XYZ (D65) through OCIO, then to CIELAB relative to a D65 white whose
// luminance is `whiteLuminance` (Y of the reference white in the images' units; 1 by
// default, i.e. lin_rec709 (1,1,1) is L* = 100). Returns a width x height map (row-major);
// with `only`, the map is computed where the mask is on and 0 elsewhere.
std::vector<float> deltaE2000Map(const Image& a, const Image& b, const std::string& spaceA = "lin_rec709",
                                 const std::string& spaceB = "lin_rec709", double whiteLuminance = 1.0,
                                 const PixelMask* only = nullptr);

struct DeltaEStats {
  double mean = 0.0, p95 = 0.0, max = 0.0;
  int64_t pixels = 0;
};
// Mean, 95th percentile and maximum of a per-pixel map over the counted pixels.
DeltaEStats deltaEStats(const std::vector<float>& map, int width, int height, const PixelMask* mask = nullptr);
DeltaEStats deltaE2000(const Image& a, const Image& b, const std::string& space = "lin_rec709",
                       const PixelMask* mask = nullptr, double whiteLuminance = 1.0);

// The p-th percentile (p in [0, 100]) with linear interpolation between order statistics:
// rank r = p/100 · (n − 1), value = v[floor r] + frac(r) · (v[floor r + 1] − v[floor r])
// (numpy's default, Hyndman-Fan type 7). Reorders `values`. NaN for an empty vector.
double percentile(std::vector<double>& values, double p);

// ---------------------------------------------------------------------------------------
// All metrics of one comparison

// Values are not clamped: values above 1 stay above 1, and negative linear values follow the
// sRGB curve's linear segment (as OpenColorIO extends it).
enum class MetricValues {
  Encoded,  // PSNR and SSIM on sRGB-encoded values (images converted to the srgb space)
  Linear,   // PSNR and SSIM on linear Rec.709 values (images converted to lin_rec709)
};
const char* metricValuesName(MetricValues v);
const char* ssimChannelsName(SsimChannels c);  // "luminance", "channels"

struct CompareOptions {
  std::string spaceA = "lin_rec709", spaceB = "lin_rec709";  // declared colour spaces
  MetricValues values = MetricValues::Encoded;
  double peak = 1.0;  // PSNR peak and SSIM dynamic range L, in the units of `values`
  SsimChannels ssimChannels = SsimChannels::Luminance;
  double whiteLuminance = 1.0;  // for CIELAB, see deltaE2000Map()
};

struct ImageMetrics {
  double psnrDb = 0.0;  // +infinity for identical values
  double ssim = 0.0;    // NaN when ssimWindows == 0
  int64_t ssimWindows = 0;
  DeltaEStats deltaE;
  // RMSE of B against A over the counted pixels and the three colour channels, relative to A's
  // mean there, on the images' own values (no colour conversion): the Monte Carlo convergence
  // measure of `inim bench`. NaN when A's mean is 0.
  double rmseRelative = 0.0;
  int64_t pixels = 0;   // pixels counted (the mask's count, or all)
  int width = 0, height = 0;
};

// Every metric of A against B. Sizes must agree (InputError naming nameA and nameB) and the
// mask must fit (InputError naming its source). `deltaEMap`: also gives the per-pixel CIEDE2000
// map the statistics were taken from (deltaE2000Map, every pixel), for callers that plot or bin it.
ImageMetrics compareImages(const Image& a, const Image& b, const CompareOptions& opt = {},
                           const PixelMask* mask = nullptr, const std::string& nameA = "A",
                           const std::string& nameB = "B", std::vector<float>* deltaEMap = nullptr);
// Reads both files (readImage: NaN/Inf are rejected) and the optional mask file.
ImageMetrics compareImageFiles(const std::string& pathA, const std::string& pathB, const CompareOptions& opt = {},
                               const std::string& maskPath = "");

// The colour space a file is assumed to be in when none is declared: EXR/HDR/PFM files are
// linear (lin_rec709), other formats (PNG, JPEG, TIFF, ...) are encoded (srgb).
std::string defaultColorSpaceForFile(const std::string& path);

// Keys: psnr_db (null when infinite), ssim (null when no window), de2000_mean, de2000_p95,
// de2000_max, pixels, ssim_windows, width, height.
Json metricsJson(const ImageMetrics& m);
// One quantity per line.
std::string metricsText(const ImageMetrics& m, const CompareOptions& opt);
// "inf" for an infinite PSNR, else %.4f (used for text and CSV reports).
std::string formatPsnr(double psnrDb);
// Rows of a per-view CSV table (e.g. Fig. 11's metrics.csv): label, psnr_db, ssim,
// de2000_mean, de2000_p95, de2000_max, pixels. Numbers as %.10g; "inf" for identical images,
// "nan" for an SSIM without windows. Quote labels with csvField() (plot.h) when writing.
std::vector<std::string> metricsCsvHeader(const std::string& labelColumn = "view");
std::vector<std::string> metricsCsvRow(const std::string& label, const ImageMetrics& m);

}  // namespace inim
