// inim triads: the RGB-wavelength triads of an EIA as a Zemax SDF source file (export), and
// an EIA formed from such a file on a detector at the panel plane (form), as the paper's NSC
// step did. The runs are src/runs/triads_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

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
  ex->add_option("--eia", e->s.eiaPath, "EIA EXR (panel or EIA size; the first three channels are R, G, B)")->required();
  ex->add_option("--out", e->s.out, "Output .sdf")->required();
  ex->add_option("--triad-wavelengths", e->s.wavelengths, "panel (default), paper, zemax-sequential or R,G,B in nm");
  ex->add_option("--flux-scale", e->s.options.fluxScale, "Flux = drive value x this (default 1)");
  ex->add_flag("--skip-zero", e->s.options.skipZeroFlux, "Leave out triad rays of flux 0 (the paper wrote them all)");
  ex->add_flag("--flux-sum", e->s.options.raySetFluxIsSum,
               "Header ray-set flux = sum of the ray fluxes (the paper wrote 1)");
  addRunOptions(ex, e->run, [e] {
    const auto t0 = std::chrono::steady_clock::now();
    e->s.displayPath = e->disp.display;
    e->s.layout = layoutOverride(e->disp);
    const TriadExportResult r = exportTriads(e->s);
    const TriadWavelengths& w = r.wavelengths;
    std::printf("wrote %llu triad rays (%llu display rays; %.6g/%.6g/%.6g nm, %s) to %s in %.2f s\n",
                (unsigned long long)r.triads, (unsigned long long)r.displayRays, w.nm[0], w.nm[1], w.nm[2],
                w.source.c_str(), e->s.out.c_str(), secondsSince(t0));
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
  fo->add_option("--sdf", f->s.sdfPath, "Zemax spectral source file (.sdf)")->required();
  fo->add_option("--out", f->s.out, "Output EXR (panel resolution, channels R, G, B: summed flux)")->required();
  fo->add_option("--png", f->s.png, "Also an encoded PNG (the panel's EOTF)");
  fo->add_option("--triad-wavelengths", f->s.wavelengths,
                 "Channels of the wavelengths: panel (default), paper, zemax-sequential or R,G,B in nm");
  f->gapOpt = fo->add_option("--gap-mm", f->gapMm, "Detector at z = -G (default: the display's generation gap)");
  addRunOptions(fo, f->run, [f] {
    const auto t0 = std::chrono::steady_clock::now();
    f->s.displayPath = f->disp.display;
    f->s.layout = layoutOverride(f->disp);
    if (f->gapOpt->count()) f->s.gapMm = f->gapMm;
    const TriadFormResult r = formTriads(f->s);
    std::printf("formed %s (%d x %d) from %s: %llu rays binned, %llu missed the detector, %llu of unknown wavelength, "
                "in %.2f s\n",
                f->s.out.c_str(), r.width, r.height, f->s.sdfPath.c_str(), (unsigned long long)r.binned,
                (unsigned long long)r.missed, (unsigned long long)r.unknownWavelength, secondsSince(t0));
    if (r.unknownWavelength)
      std::fprintf(stderr,
                   "inim: warning: %llu rays have none of the triad wavelengths %.6g/%.6g/%.6g nm (within 0.5 nm); "
                   "check --triad-wavelengths\n",
                   (unsigned long long)r.unknownWavelength, r.wavelengths.nm[0], r.wavelengths.nm[1],
                   r.wavelengths.nm[2]);
  });
}

}  // namespace inim::cli
