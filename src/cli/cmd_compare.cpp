// inim compare A B [--json] [--mask FILE] [--space NAME] ...: full-reference image metrics of
// A against B: PSNR, SSIM, and the mean and 95th percentile of the per-pixel CIEDE2000. The run
// is src/runs/compare_run.h.
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "runs/compare_run.h"

namespace inim::cli {

void addCompareCommand(CLI::App& app) {
  struct Opts {
    CompareRunSettings s;  // the options write it directly
    bool json = false;
  };
  auto opts = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("A", opts->s.a, "First image (e.g. the reference)")->required();
  cmd->add_option("B", opts->s.b, "Second image (e.g. the reconstruction); same size as A")->required();
  cmd->add_flag("--json", opts->json,
                "Print JSON: psnr_db (null if identical), ssim, de2000_mean, de2000_p95, de2000_max, pixels, ...");
  cmd->add_option("--mask", opts->s.mask,
                  "Mask image of the same size: a single-channel image or the alpha of an image; pixels with "
                  "value > 0.5 count, the others have no influence on any metric");
  cmd->add_option("--space", opts->s.space,
                  "Colour space of both images (lin_rec709, srgb, display_p3, acescg, cie_xyz_d65); default: "
                  "lin_rec709 for EXR/HDR files, srgb for PNG/JPEG/TIFF, per file");
  const std::map<std::string, MetricValues> values = {{"encoded", MetricValues::Encoded},
                                                      {"linear", MetricValues::Linear}};
  cmd->add_option("--values", opts->s.options.values,
                  "PSNR and SSIM on sRGB-encoded values (encoded) or on linear Rec.709 values (linear)")
      ->transform(CLI::CheckedTransformer(values))
      ->default_str(opts->s.options.values == MetricValues::Encoded ? "encoded" : "linear");
  cmd->add_option("--peak", opts->s.options.peak, "PSNR peak value and SSIM dynamic range L, in the units of --values")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  const std::map<std::string, SsimChannels> ssim = {{"luminance", SsimChannels::Luminance},
                                                    {"channels", SsimChannels::PerChannelMean}};
  cmd->add_option("--ssim", opts->s.options.ssimChannels,
                  "SSIM on luminance, or the mean of per-channel SSIMs (channels)")
      ->transform(CLI::CheckedTransformer(ssim))
      ->default_str(opts->s.options.ssimChannels == SsimChannels::Luminance ? "luminance" : "channels");
  cmd->add_option("--white-luminance", opts->s.options.whiteLuminance,
                  "Y of the reference white for CIELAB, in the images' linear units (1: RGB (1,1,1) is L* = 100)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--de-map", opts->s.deMap, "Also write the per-pixel CIEDE2000 as a single-channel EXR");
  cmd->callback([opts] {
    const CompareRunResult r = runCompare(opts->s);
    std::printf("%s", (opts->json ? compareJson(opts->s, r) : compareText(opts->s, r)).c_str());
  });
}

}  // namespace inim::cli
