// inim triads: the RGB-wavelength triads of an EIA as a Zemax SDF source file (export), and
// an EIA formed from such a file on a detector at the panel plane (form), as the paper's NSC
// step did. The runs are src/runs/triads_run.h.
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/triads_run.h"

namespace inim::cli {

void addTriadsCommand(CLI::App& app) {
  CLI::App* triads = &app;
  triads->require_subcommand(1);

  // inim triads export
  struct ExportOpts {
    DisplayArgs disp;
    TriadExportSettings s;
    RunOptions run;
  };
  auto e = std::make_shared<ExportOpts>();
  auto* ex = triads->add_subcommand(
      "export", "EIA (EXR of drive values) -> 3 monochromatic rays per display ray, as a Zemax spectral SDF source file");
  addDisplayOptions(ex, e->disp);
  addSetting(ex, "eia", e->s.eiaPath)->required();
  addSetting(ex, "out", e->s.out)->required();
  addSetting(ex, "triad_wavelengths", e->s.wavelengths);
  addSetting(ex, "flux_scale", e->s.options.fluxScale);
  addSetting(ex, "skip_zero", e->s.options.skipZeroFlux);
  addSetting(ex, "flux_sum", e->s.options.raySetFluxIsSum);
  addRunOptions(ex, e->run, [e] {
    const auto t0 = std::chrono::steady_clock::now();
    e->s.displayPath = e->disp.display.value_or("");
    e->s.layout = layoutOverride(e->disp);
    const TriadExportResult r = exportTriads(e->s);
    std::printf("%s", exportText(e->s, r, secondsSince(t0)).c_str());
  });

  // inim triads form
  struct FormOpts {
    DisplayArgs disp;
    TriadFormSettings s;
    double gapMm = 0.0;
    CLI::Option* gapOpt = nullptr;
    RunOptions run;
  };
  auto f = std::make_shared<FormOpts>();
  auto* fo = triads->add_subcommand(
      "form", "Zemax SDF triads -> EIA: straight propagation to a detector at the panel plane z = -g, flux binned per "
              "pixel and channel");
  addDisplayOptions(fo, f->disp);
  addSetting(fo, "sdf", f->s.sdfPath)->required();
  addSetting(fo, "out", f->s.out)->required();
  addSetting(fo, "png", f->s.png);
  addSetting(fo, "triad_wavelengths", f->s.wavelengths);
  f->gapOpt = addSetting(fo, "gap_mm", f->gapMm);
  addRunOptions(fo, f->run, [f] {
    const auto t0 = std::chrono::steady_clock::now();
    f->s.displayPath = f->disp.display.value_or("");
    f->s.layout = layoutOverride(f->disp);
    if (f->gapOpt->count()) f->s.gapMm = f->gapMm;
    const TriadFormResult r = formTriads(f->s);
    std::printf("%s", formText(f->s, r, secondsSince(t0)).c_str());
    std::fprintf(stderr, "%s", formWarning(r).c_str());
  });
}

}  // namespace inim::cli
