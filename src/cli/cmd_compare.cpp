// inim compare A B [--json] [--mask FILE] [--space NAME] ...: full-reference image metrics of
// A against B: PSNR, SSIM, and the mean and 95th percentile of the per-pixel CIEDE2000. The run
// is src/runs/compare_run.h.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
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
  CompareOptions& co = opts->s.options;
  addChoiceOption(cmd, "--values", co.values, {MetricValues::Encoded, MetricValues::Linear}, metricValuesName,
                  "PSNR and SSIM on sRGB-encoded values or on linear Rec.709 values")
      ->default_str(metricValuesName(co.values));
  cmd->add_option("--peak", opts->s.options.peak, "PSNR peak value and SSIM dynamic range L, in the units of --values")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  addChoiceOption(cmd, "--ssim", co.ssimChannels, {SsimChannels::Luminance, SsimChannels::PerChannelMean},
                  ssimChannelsName, "SSIM on luminance, or the mean of per-channel SSIMs")
      ->default_str(ssimChannelsName(co.ssimChannels));
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
