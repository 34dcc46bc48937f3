// inim compare A B [--json] [--mask FILE] [--space NAME] ...: full-reference image metrics of
// A against B: PSNR, SSIM, and the mean and 95th percentile of the per-pixel CIEDE2000. The run
// is src/runs/compare_run.h.
#include <cstdio>
#include <memory>

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
  addSetting(cmd, "json", opts->json);
  addSetting(cmd, "mask", opts->s.mask);
  addSetting(cmd, "space", opts->s.space);
  CompareOptions& co = opts->s.options;
  addChoiceSetting(cmd, "values", co.values, {MetricValues::Encoded, MetricValues::Linear}, metricValuesName);
  addSetting(cmd, "peak", opts->s.options.peak);
  addChoiceSetting(cmd, "ssim", co.ssimChannels, {SsimChannels::Luminance, SsimChannels::PerChannelMean},
                   ssimChannelsName);
  addSetting(cmd, "white_luminance", opts->s.options.whiteLuminance);
  addSetting(cmd, "de_map", opts->s.deMap);
  cmd->callback([opts] {
    const CompareRunResult r = runCompare(opts->s);
    std::printf("%s", (opts->json ? compareJson(opts->s, r) : compareText(opts->s, r)).c_str());
  });
}

}  // namespace inim::cli
