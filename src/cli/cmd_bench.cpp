// inim bench: speed benchmarks on Google Benchmark (src/bench/benchmarks.h lists them), with
// ratios measured in one run.
#include <memory>

#include "bench/benchmarks.h"
#include "cli/commands.h"
#include "cli/options.h"

namespace inim::cli {

void addBenchCommand(CLI::App& app) {
  struct Opts {
    BenchSettings s;
    std::vector<std::string> viewEstimators = {"point", "footprint", "quadrature"};
    std::string fieldScale, fieldRotate, fieldTranslate;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  ViewBenchSettings& v = o->s.view;
  RadianceBenchSettings& r = o->s.radiance;
  CLI::App* cmd = &app;
  addSetting(cmd, "filter", o->s.filter);
  addSetting(cmd, "min_time", o->s.minTime);
  addSetting(cmd, "view_width", v.width);
  addSetting(cmd, "view_spp", v.spps);
  addSetting(cmd, "view_estimators", o->viewEstimators);
  addSetting(cmd, "view_ref_spp", v.referenceSpp);
  addSetting(cmd, "view_grid", v.grid);
  addSetting(cmd, "view_ref_grid", v.referenceGrid);
  addSetting(cmd, "field_model", r.modelPath);
  addSetting(cmd, "field_scale", o->fieldScale);
  addSetting(cmd, "field_rotate_deg", o->fieldRotate);
  addSetting(cmd, "field_translate_mm", o->fieldTranslate);
  addSetting(cmd, "lego", r.legoDir);
  addSetting(cmd, "lego_iterations", r.legoIterations);
  addRunOptions(cmd, o->run, [o] {
    o->s.view.estimators.clear();
    for (const auto& e : o->viewEstimators) parsePanelEstimator(e, o->s.view.estimators.emplace_back());
    o->s.radiance.placement = parsePlacementOverride(o->fieldScale, o->fieldRotate, o->fieldTranslate, "field_");
    o->s.threads = o->run.threads;
    runBenchmarks(o->s);
  });
}

}  // namespace inim::cli
