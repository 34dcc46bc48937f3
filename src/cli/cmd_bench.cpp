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
  cmd->add_option("--filter", o->s.filter, "Regex of benchmarks to run")->capture_default_str();
  cmd->add_option("--min-time", o->s.minTime, "Minimum seconds per benchmark")->capture_default_str();
  cmd->add_option("--view-width", v.width, "Image width of the view/ benchmarks (2592 = the sensor)")
      ->capture_default_str();
  cmd->add_option("--view-spp", v.spps, "Samples per pixel of the view/ benchmarks")
      ->delimiter(',')->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--view-estimators", o->viewEstimators, "Panel estimators of the view/ benchmarks")
      ->delimiter(',')->check(CLI::IsMember({"point", "footprint", "quadrature"}))->capture_default_str();
  cmd->add_option("--view-ref-spp", v.referenceSpp, "spp of view/reference; 0: 16x the largest --view-spp")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("--view-grid", v.grid, "Aperture table grid of the quadrature view/ runs")
      ->check(CLI::Range(2, 64))->capture_default_str();
  cmd->add_option("--view-ref-grid", v.referenceGrid,
                  "Aperture table grid of their references (0: --view-grid; larger: the table's own error shows "
                  "in the RMSE)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  cmd->add_option("--field-model", r.modelPath, "Trained model (.inimrf) for radiance/eia-query and the place/ model runs");
  cmd->add_option("--field-scale", o->fieldScale, "Its placement scale, mm per field unit (default: the model's)");
  cmd->add_option("--field-rotate-deg", o->fieldRotate, "Its placement rotation rx,ry,rz, degrees");
  cmd->add_option("--field-translate-mm", o->fieldTranslate, "Its placement translation, mm");
  cmd->add_option("--lego", r.legoDir, "Lego dataset folder for radiance/train-lego (e.g. ../shared/data/lego)");
  cmd->add_option("--lego-iterations", r.legoIterations, "Training iterations of radiance/train-lego")
      ->capture_default_str();
  addRunOptions(cmd, o->run, [o] {
    o->s.view.estimators.clear();
    for (const auto& e : o->viewEstimators) parsePanelEstimator(e, o->s.view.estimators.emplace_back());
    PlacementOverride& p = o->s.radiance.placement;
    if (!o->fieldScale.empty()) p.scale = parseVec3(o->fieldScale, "--field-scale", true);
    if (!o->fieldRotate.empty()) p.rotateDeg = parseVec3(o->fieldRotate, "--field-rotate-deg");
    if (!o->fieldTranslate.empty()) p.translateMm = parseVec3(o->fieldTranslate, "--field-translate-mm");
    o->s.threads = o->run.threads;
    runBenchmarks(o->s);
  });
}

}  // namespace inim::cli
