// inim compare A B [--json] [--mask FILE] [--space NAME] ...: full-reference image metrics of
// A against B: PSNR, SSIM, and the mean and 95th percentile of the per-pixel CIEDE2000.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "core/format.h"
#include "analysis/metrics.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "core/output_file.h"
#include "spectral/color.h"

namespace inim::cli {

namespace {

// InputError naming the option when the config has no such colour space.
void checkSpace(const std::string& space, const std::string& option) {
  try {
    ColorSystem::instance().convert(Vec3(0.0f), space, "cie_xyz_d65");
  } catch (const InputError& e) {
    throw InputError("", option, space, e.expected());
  }
}

}  // namespace

void addCompareCommand(CLI::App& app) {
  struct Opts {
    std::string a, b, mask, space, deMap;
    std::string values = "encoded";
    std::string ssim = "luminance";
    double peak = 1.0;
    double white = 1.0;
    bool json = false;
  };
  auto opts = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "compare",
      "Image metrics of A against B: PSNR, SSIM (Wang et al. 2004, 11x11 Gaussian, sigma 1.5) and CIEDE2000 (mean, "
      "95th percentile, max)");
  cmd->add_option("A", opts->a, "First image (e.g. the reference)")->required();
  cmd->add_option("B", opts->b, "Second image (e.g. the reconstruction); same size as A")->required();
  cmd->add_flag("--json", opts->json,
                "Print JSON: psnr_db (null if identical), ssim, de2000_mean, de2000_p95, de2000_max, pixels, ...");
  cmd->add_option("--mask", opts->mask,
                  "Mask image of the same size: a single-channel image or the alpha of an image; pixels with "
                  "value > 0.5 count, the others have no influence on any metric");
  cmd->add_option("--space", opts->space,
                  "Colour space of both images (lin_rec709, srgb, display_p3, acescg, cie_xyz_d65); default: "
                  "lin_rec709 for EXR/HDR files, srgb for PNG/JPEG/TIFF, per file");
  cmd->add_option("--values", opts->values,
                  "PSNR and SSIM on sRGB-encoded values (encoded) or on linear Rec.709 values (linear)")
      ->check(CLI::IsMember({"encoded", "linear"}))
      ->capture_default_str();
  cmd->add_option("--peak", opts->peak, "PSNR peak value and SSIM dynamic range L, in the units of --values")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--ssim", opts->ssim, "SSIM on luminance, or the mean of per-channel SSIMs (channels)")
      ->check(CLI::IsMember({"luminance", "channels"}))
      ->capture_default_str();
  cmd->add_option("--white-luminance", opts->white,
                  "Y of the reference white for CIELAB, in the images' linear units (1: RGB (1,1,1) is L* = 100)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--de-map", opts->deMap, "Also write the per-pixel CIEDE2000 as a single-channel EXR");
  cmd->callback([opts] {
    CompareOptions co;
    co.spaceA = opts->space.empty() ? defaultColorSpaceForFile(opts->a) : opts->space;
    co.spaceB = opts->space.empty() ? defaultColorSpaceForFile(opts->b) : opts->space;
    if (!opts->space.empty()) checkSpace(opts->space, "--space");
    co.values = opts->values == "linear" ? MetricValues::Linear : MetricValues::Encoded;
    co.peak = opts->peak;
    co.ssimChannels = opts->ssim == "channels" ? SsimChannels::PerChannelMean : SsimChannels::Luminance;
    co.whiteLuminance = opts->white;

    const std::string mapExt = lowerExtension(opts->deMap);
    if (!opts->deMap.empty() && mapExt != ".exr")
      throw InputError("", "--de-map", opts->deMap, "an .exr file (the map holds unbounded float values)");
    const Image a = readImage(opts->a), b = readImage(opts->b);  // InputError for NaN / Inf
    requireSameSize(a, b, opts->a, opts->b);
    std::unique_ptr<PixelMask> mask;
    if (!opts->mask.empty()) {
      mask = std::make_unique<PixelMask>(loadMask(opts->mask));
      requireMaskFits(*mask, a.width, a.height);
    }
    const ImageMetrics m = compareImages(a, b, co, mask.get(), opts->a, opts->b);

    if (!opts->deMap.empty()) {
      OutputSet out;
      const std::string tmp = out.add(opts->deMap);
      Image map(a.width, a.height, {"Y"});
      map.data = deltaE2000Map(a, b, co.spaceA, co.spaceB, co.whiteLuminance);
      writeImage(map, tmp);
      out.commit();
    }

    if (opts->json) {
      Json j = metricsJson(m);
      j["a"] = opts->a;
      j["b"] = opts->b;
      j["mask"] = opts->mask.empty() ? Json(nullptr) : Json(opts->mask);
      j["space_a"] = co.spaceA;
      j["space_b"] = co.spaceB;
      j["values"] = metricValuesName(co.values);
      j["peak"] = co.peak;
      j["ssim_channels"] = opts->ssim;
      j["white_luminance"] = co.whiteLuminance;
      std::printf("%s\n", j.dump(2).c_str());
    } else {
      std::printf("A            %s\nB            %s\n", opts->a.c_str(), opts->b.c_str());
      if (!opts->mask.empty()) std::printf("mask         %s\n", opts->mask.c_str());
      std::printf("%s", metricsText(m, co).c_str());
    }
  });
}

}  // namespace inim::cli
