// inim triads: the RGB-wavelength triads of an EIA as a Zemax SDF source file (export), and
// an EIA formed from such a file on a detector at the panel plane (form), as the paper's NSC
// step did. See src/triads/triads.h.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/format.h"
#include "core/image.h"
#include "core/output_file.h"
#include "core/progress.h"
#include "rays/pinhole_rays.h"
#include "synthesis/eia_synthesis.h"
#include "triads/sdf.h"
#include "triads/triads.h"

namespace inim::cli {

void addTriadsCommand(CLI::App& app) {
  auto* triads = app.add_subcommand("triads", "RGB-wavelength triads: Zemax SDF export and EIA formation");
  triads->require_subcommand(1);

  // inim triads export
  struct ExportOpts {
    DisplayArgs disp;
    std::string eia, out, wavelengths = "panel";
    float fluxScale = 1.0f;
    bool skipZero = false, fluxSum = false;
    RunOptions run;
  };
  auto e = std::make_shared<ExportOpts>();
  auto* ex = triads->add_subcommand(
      "export", "EIA (EXR of drive values) -> 3 monochromatic rays per display ray, as a Zemax spectral SDF source file");
  addDisplayOptions(ex, e->disp);
  ex->add_option("--eia", e->eia, "EIA EXR (panel or EIA size; the first three channels are R, G, B)")->required();
  ex->add_option("--out", e->out, "Output .sdf")->required();
  ex->add_option("--triad-wavelengths", e->wavelengths, "panel (default), paper, zemax-sequential or R,G,B in nm");
  ex->add_option("--flux-scale", e->fluxScale, "Flux = drive value x this (default 1)");
  ex->add_flag("--skip-zero", e->skipZero, "Leave out triad rays of flux 0 (the paper wrote them all)");
  ex->add_flag("--flux-sum", e->fluxSum, "Header ray-set flux = sum of the ray fluxes (the paper wrote 1)");
  addRunOptions(ex, e->run, [e] {
    auto t0 = std::chrono::steady_clock::now();
    if (lowerExtension(e->out) != ".sdf" && lowerExtension(e->out) != ".dat")
      throw InputError("", "--out", "\"" + e->out + "\"", "a Zemax source file name (.sdf or .dat)");
    if (!(e->fluxScale > 0.0f) || !std::isfinite(e->fluxScale))
      throw InputError("", "--flux-scale", std::to_string(e->fluxScale), "a number > 0");
    Display d;
    EiLayout L = loadDisplayLayout(e->disp, d);
    TriadWavelengths w = parseTriadWavelengths(d.panel, e->wavelengths);
    Image img = readImage(e->eia);
    Image area = eiaArea(L, img, e->eia);
    std::vector<float> drive = driveFromEia(L, area);
    RaySet rays = generatePinholeRays(L);
    TriadOptions to;
    to.fluxScale = e->fluxScale;
    to.skipZeroFlux = e->skipZero;
    to.raySetFluxIsSum = e->fluxSum;
    to.description = "inim triads: " + d.name + ", " + w.source;
    OutputSet outputs;
    ProgressBar bar("triads", uint64_t(rays.size()) * 3);
    uint64_t n = writeTriadSdf(outputs.add(e->out), rays, drive, w, to, &bar);
    bar.finish();
    outputs.commit();
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("wrote %llu triad rays (%llu display rays; %.6g/%.6g/%.6g nm, %s) to %s in %.2f s\n",
                (unsigned long long)n, (unsigned long long)rays.size(), w.nm[0], w.nm[1], w.nm[2], w.source.c_str(),
                e->out.c_str(), s);
  });

  // inim triads form
  struct FormOpts {
    DisplayArgs disp;
    std::string sdf, out, png, wavelengths = "panel";
    double gapMm = 0.0;
    CLI::Option* gapOpt = nullptr;
    RunOptions run;
  };
  auto f = std::make_shared<FormOpts>();
  auto* fo = triads->add_subcommand(
      "form", "Zemax SDF triads -> EIA: straight propagation to a detector at the panel plane z = -g, flux binned per "
              "pixel and channel");
  addDisplayOptions(fo, f->disp);
  fo->add_option("--sdf", f->sdf, "Zemax spectral source file (.sdf)")->required();
  fo->add_option("--out", f->out, "Output EXR (panel resolution, channels R, G, B: summed flux)")->required();
  fo->add_option("--png", f->png, "Also an encoded PNG (the panel's EOTF)");
  fo->add_option("--triad-wavelengths", f->wavelengths,
                 "Channels of the wavelengths: panel (default), paper, zemax-sequential or R,G,B in nm");
  f->gapOpt = fo->add_option("--gap-mm", f->gapMm, "Detector at z = -G (default: the display's generation gap)");
  addRunOptions(fo, f->run, [f] {
    auto t0 = std::chrono::steady_clock::now();
    if (lowerExtension(f->out) != ".exr") throw InputError("", "--out", "\"" + f->out + "\"", "an OpenEXR file name (.exr)");
    if (!f->png.empty() && lowerExtension(f->png) != ".png")
      throw InputError("", "--png", "\"" + f->png + "\"", "a PNG file name (.png)");
    Display d;
    EiLayout L = loadDisplayLayout(f->disp, d);
    if (f->gapOpt->count()) L = L.withGap(checkedGap(f->gapMm, std::to_string(f->gapMm)));
    TriadWavelengths w = parseTriadWavelengths(d.panel, f->wavelengths);
    EiaFormation formed = formEiaFromSdf(L, f->sdf, w);
    Image eia = onPanel(L, formed.eia);
    OutputSet outputs;
    writeImage(eia, outputs.add(f->out));
    if (!f->png.empty()) writeImage(encodeForPanel(eia, d.panel.eotf), outputs.add(f->png));
    outputs.commit();
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("formed %s (%d x %d) from %s: %llu rays binned, %llu missed the detector, %llu of unknown wavelength, "
                "in %.2f s\n",
                f->out.c_str(), eia.width, eia.height, f->sdf.c_str(), (unsigned long long)formed.binned,
                (unsigned long long)formed.missed, (unsigned long long)formed.unknownWavelength, s);
    if (formed.unknownWavelength)
      std::fprintf(stderr,
                   "inim: warning: %llu rays have none of the triad wavelengths %.6g/%.6g/%.6g nm (within 0.5 nm); "
                   "check --triad-wavelengths\n",
                   (unsigned long long)formed.unknownWavelength, w.nm[0], w.nm[1], w.nm[2]);
  });
}

}  // namespace inim::cli
