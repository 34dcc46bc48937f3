// inim eia: orthoscopic elemental-image synthesis. Display + scene (a Field) + placement ->
// the EIA at the panel's full resolution: a linear EXR of drive values (+ A, Z with --aovs),
// an encoded PNG beside it, and optionally the placement preview and the triads as a Zemax
// SDF source file. See src/synthesis/eia_synthesis.h.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>
#include <memory>
#include <string>

#include "core/format.h"
#include "cli/commands.h"
#include "cli/scene_options.h"
#include "core/error.h"
#include "core/image.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "display/display.h"
#include "field/ray_table.h"
#include "mla/real_lens_rays.h"
#include "mla/real_mla.h"
#include "rays/pinhole_rays.h"
#include "scene/analytic_scene.h"
#include "synthesis/display_overrides.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"
#include "triads/triads.h"

namespace fs = std::filesystem;

namespace inim::cli {

namespace {

void requireExt(const std::string& path, const std::string& key, std::initializer_list<const char*> exts,
                const std::string& what) {
  std::string e = lowerExtension(path);
  for (const char* x : exts)
    if (e == x) return;
  throw InputError("", key, "\"" + path + "\"", what);
}

}  // namespace

void addEiaCommand(CLI::App& app) {
  struct Opts {
    std::string display, scene, field, fieldColors, colorsEncoding = "srgb", out, png, sdf, run, preview;
    PlacementArgs place;
    std::string triads, layout, exposure, gamut, whiteBalance, realLensRay = "centroid";
    double vcpMm = kDefaultVcpMm, viewingDistanceMm = 0.0, wavelengthNm = kLambdaDNm;
    int spp = 1;
    bool aovs = false, quiet = false, realLens = false;
    RunOptions runOpts;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "eia", "Orthoscopic EIA synthesis: query the scene along every reversed display ray from the VCP and write the "
             "panel drive values");
  cmd->add_option("--display", o->display, "Display JSON (default: optics/displays/paper-prototype.json)");
  auto* sceneOpt = cmd->add_option("--scene", o->scene, "Scene JSON (default: scenes/paper-fig7.json)");
  auto* fieldOpt = cmd->add_option("--field", o->field, "The field to show: a scene JSON or a trained radiance field (.inimrf)");
  auto* colorsOpt = cmd->add_option("--field-colors", o->fieldColors,
                                    "Colours of an external field, one per query ray written by `inim rays --for-field` "
                                    "with the same display, placement and settings (.npy or .exr: R G B [A [depth]])");
  cmd->add_option("--field-colors-encoding", o->colorsEncoding,
                  "srgb (NeRF outputs, default) or linear: how --field-colors values are encoded")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output EXR of linear drive values at the panel resolution")->required();
  auto* pngOpt = cmd->add_option("--png", o->png, "Encoded PNG (default: beside --out, same name, .png)");
  cmd->add_option("--sdf", o->sdf, "Also write the triads (3 rays per display ray) as a Zemax SDF source file");
  auto* triOpt = cmd->add_option("--triad-wavelengths", o->triads,
                                 "Triad wavelengths: panel (primary peaks, default), paper (656,566,471), "
                                 "zemax-sequential (620,525,460) or R,G,B in nm");
  addPlacementOptions(cmd, o->place);
  cmd->add_option("--run", o->run, "Run file (JSON): placement and settings; command-line options override it");
  auto* vcpOpt = cmd->add_option("--vcp-mm", o->vcpMm,
                                 "VCP distance D_VCP in front of the MLA (the near clipping plane), mm")
                     ->capture_default_str();
  auto* layoutOpt = cmd->add_option("--layout", o->layout, "EI layout: parallel, toed-in or lens-grid");
  auto* distOpt = cmd->add_option("--viewing-distance-mm", o->viewingDistanceMm, "Viewing distance D for toed-in");
  auto* sppOpt = cmd->add_option("--spp", o->spp, "Field samples per display ray (wavelengths, light samples)")
                     ->capture_default_str();
  auto* expOpt = cmd->add_option("--exposure", o->exposure,
                                 "Drive = E x panel-native RGB (field luminance 1/E = panel white), or auto (default: the "
                                 "99th percentile of the brightest channel of the pixels that see the scene -> full "
                                 "drive)");
  auto* gamutOpt = cmd->add_option("--gamut", o->gamut, "Out-of-gamut mapping: clip (per channel, default) or desaturate");
  auto* wbOpt = cmd->add_option("--white-balance", o->whiteBalance,
                                "none (colorimetric, default) or d65 (gains so that D65 drives 1,1,1)");
  cmd->add_flag("--real-lens", o->realLens,
                "Query the scene along the real-lens display rays (traced through the refracting MLA at the physical "
                "lens centres) instead of the pinhole rays");
  auto* realRayOpt = cmd->add_option("--real-lens-ray", o->realLensRay,
                                     "With --real-lens: centroid (power centroid of each pixel's exit bundle, default) "
                                     "or chief (the ray through the lenslet's aperture centre)");
  auto* wlOpt = cmd->add_option("--wavelength-nm", o->wavelengthNm, "With --real-lens: the wavelength, nm")
                    ->capture_default_str();
  cmd->add_flag("--aovs", o->aovs, "Add A (opacity) and Z (display z of the first surface, mm) channels to the EXR");
  cmd->add_option("--preview", o->preview, "Placement preview PNG (central ray of each lenslet, like the paper's Fig. 4)");
  cmd->add_flag("--quiet", o->quiet, "Print nothing but warnings");
  addRunOptions(cmd, o->runOpts);
  auto* seedOpt = cmd->get_option("--seed");

  cmd->callback([=] {
    ThreadLimit threads(o->runOpts.threads);
    if (o->colorsEncoding != "srgb" && o->colorsEncoding != "linear")
      throw InputError("", "--field-colors-encoding", "\"" + o->colorsEncoding + "\"", "srgb or linear");
    const auto t0 = std::chrono::steady_clock::now();

    // Settings: defaults < run file < command line.
    RunFile run;
    if (!o->run.empty()) run = loadRunFile(o->run);
    SynthesisSettings s;
    if (int(sceneOpt->count()) + int(fieldOpt->count()) + int(colorsOpt->count()) > 1)
      throw InputError("", "--field", "more than one of --scene, --field, --field-colors", "one field source");
    // The field first: a trained field carries its own default placement (run file and
    // command line override it).
    LoadedField lf;
    if (!colorsOpt->count()) {
      std::string path = sceneOpt->count()   ? o->scene
                         : fieldOpt->count() ? o->field
                                             : run.scene.value_or(dataPath("scenes/paper-fig7.json"));
      lf = loadField(path, fieldOpt->count() ? "--field" : "--scene");
    }
    s.placement = resolvePlacement(o->place, run.placement ? run.placement : lf.placement);
    s.vcpMm = vcpOpt->count() ? o->vcpMm : run.vcpMm.value_or(kDefaultVcpMm);
    if (!std::isfinite(s.vcpMm)) throw InputError("", "--vcp-mm", formatNumber(s.vcpMm), "a finite distance in mm");
    s.spp = sppOpt->count() ? o->spp : run.spp.value_or(1);
    if (s.spp < 1) throw InputError("", "--spp", std::to_string(s.spp), "a whole number >= 1");
    s.seed = seedOpt->count() ? o->runOpts.seed : run.seed.value_or(o->runOpts.seed);
    std::string exposure = expOpt->count() ? o->exposure : run.exposure.value_or("auto");
    if (exposure == "auto") {
      s.autoExposure = true;
    } else {
      char* end = nullptr;
      s.exposure = std::strtod(exposure.c_str(), &end);
      if (exposure.empty() || *end || !(s.exposure > 0.0) || !std::isfinite(s.exposure))
        throw InputError(expOpt->count() ? "" : run.file, expOpt->count() ? "--exposure" : "exposure",
                         "\"" + exposure + "\"", "a number > 0 or auto");
    }
    s.gamut = parseGamut(gamutOpt->count() ? o->gamut : run.gamut.value_or("clip"));
    std::string wb = wbOpt->count() ? o->whiteBalance : run.whiteBalance.value_or("none");
    if (wb != "none" && wb != "d65") throw InputError("", "--white-balance", "\"" + wb + "\"", "none or d65");
    s.whiteBalanceD65 = wb == "d65";
    s.aovs = o->aovs;
    s.progress = !o->quiet;

    // Outputs: checked before the work starts.
    requireExt(o->out, "--out", {".exr"}, "an OpenEXR file name (.exr)");
    std::string png = pngOpt->count() ? o->png : (fs::path(o->out).replace_extension(".png")).string();
    requireExt(png, "--png", {".png"}, "a PNG file name (.png)");
    if (!o->preview.empty()) requireExt(o->preview, "--preview", {".png"}, "a PNG file name (.png)");
    if (!o->sdf.empty()) requireExt(o->sdf, "--sdf", {".sdf", ".dat"}, "a Zemax source file name (.sdf or .dat)");

    // Display and layout.
    std::string displayPath = displayPathOrDefault(!o->display.empty() ? o->display : run.display.value_or(""));
    Display d = loadDisplay(displayPath);
    LayoutOverride lo;
    if (layoutOpt->count()) lo.layout = o->layout;
    else if (run.layout) lo.layout = *run.layout, lo.layoutKey = "layout (" + run.file + ")";
    if (distOpt->count()) lo.viewingDistanceMm = o->viewingDistanceMm;
    else if (run.viewingDistanceMm)
      lo.viewingDistanceMm = *run.viewingDistanceMm, lo.distanceKey = "viewing_distance_mm (" + run.file + ")";
    const EiLayout L = applyLayoutOverride(d, lo);
    // Real-lens display rays.
    if (!o->realLens && (realRayOpt->count() || wlOpt->count()))
      throw InputError("", realRayOpt->count() ? "--real-lens-ray" : "--wavelength-nm",
                       realRayOpt->count() ? "\"" + o->realLensRay + "\"" : formatNumber(o->wavelengthNm),
                       "--real-lens as well (the pinhole model has no refraction)");
    RaySet realRays;
    RealLensRayOptions ro;
    RealLensRayStats realStats;
    if (o->realLens) {
      ro.model = parseRealLensRayModel(o->realLensRay, "--real-lens-ray");
      if (!(o->wavelengthNm >= 360.0 && o->wavelengthNm <= 830.0))
        throw InputError("", "--wavelength-nm", formatNumber(o->wavelengthNm), "a wavelength in 360-830 nm");
      ro.wavelengthNm = o->wavelengthNm;
      std::unique_ptr<RealMla> mla = RealMla::fromDisplay(d, L, L.gapMm);
      ProgressBar bar("real-lens rays", uint64_t(L.numRays()), !o->quiet && ProgressBar::stderrIsTerminal());
      realRays = generateRealLensRays(L, *mla, ro, &realStats, &bar);
      bar.finish();
      s.displayRays = &realRays;
    }
    std::string triChoice = triOpt->count() ? o->triads : run.triadWavelengths.value_or("panel");
    const TriadWavelengths tw = parseTriadWavelengths(d.panel, triChoice);

    if (colorsOpt->count()) {
      Point3 lo(-1e6f), hi(1e6f);  // an external field's extent is unknown
      auto f = std::make_unique<ColorTableField>(ColorTableField::load(
          o->fieldColors, s.spp, size_t(L.numRays()) * size_t(s.spp),
          o->colorsEncoding == "srgb" ? ColorEncoding::SRGB : ColorEncoding::Linear, lo, hi));
      lf.field = std::move(f);
      lf.path = o->fieldColors;
      lf.kind = "external field colours";
    }
    const Field& field = *lf.field;
    if (!o->quiet) {
      if (L.isHex())
        std::printf("display:     %s (%s layout, hex lattice: %d rows of %d EIs, %d px across the flats, g = %s mm; "
                    "panel %d x %d px)\n",
                    d.name.c_str(), layoutName(L.kind), L.eiRows, L.eiCols, d.eiWidthPx, formatNumber(L.gapMm).c_str(),
                    L.panelW, L.panelH);
      else
        std::printf("display:     %s (%s layout, %d x %d EIs of %d x %d px, g = %s mm; panel %d x %d px)\n",
                    d.name.c_str(), layoutName(L.kind), L.eiCols, L.eiRows, L.eiW, L.eiH, formatNumber(L.gapMm).c_str(),
                    L.panelW, L.panelH);
      std::printf("field:       %s (%s)\n", lf.path.c_str(), lf.kind.c_str());
      std::printf("placement:   %s; VCP at z = %s mm\n", s.placement.describe().c_str(), formatNumber(s.vcpMm).c_str());
      if (o->realLens) std::printf("rays:        %s\n", summaryText(ro, realStats).c_str());
      std::fflush(stdout);
    }

    const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    SynthesisResult r = synthesizeEia(L, d.panel, field, s);

    // Outputs: each to a temporary, written concurrently (EXR and PNG compression are single
    // threaded), renamed into place together only when all succeeded.
    const auto tw0 = std::chrono::steady_clock::now();
    OutputSet outputs;
    const std::string exrTmp = outputs.add(o->out), pngTmp = outputs.add(png);
    const std::string previewTmp = o->preview.empty() ? "" : outputs.add(o->preview);
    const std::string sdfTmp = o->sdf.empty() ? "" : outputs.add(o->sdf);
    PreviewResult pv;
    if (!o->preview.empty()) {
      PreviewSettings ps;
      ps.seed = s.seed;
      pv = renderPlacementPreview(L, field, s.placement.toDisplay(), s.vcpMm, ps);
    }
    std::vector<std::future<void>> writes;
    writes.push_back(std::async(std::launch::async, [&] { writeImage(r.eia, exrTmp); }));
    writes.push_back(std::async(std::launch::async, [&] { writeImage(encodeForPanel(r.eia, d.panel.eotf), pngTmp); }));
    if (!previewTmp.empty()) writes.push_back(std::async(std::launch::async, [&] { writeImage(pv.image, previewTmp); }));
    uint64_t triads = 0;
    if (!sdfTmp.empty()) {
      RaySet rays = o->realLens ? realRays : generatePinholeRays(L);
      TriadOptions to;
      to.description = "inim triads: " + d.name + ", " + tw.source;
      ProgressBar bar("triads", uint64_t(L.numRays()) * 3, !o->quiet && ProgressBar::stderrIsTerminal());
      triads = writeTriadSdf(sdfTmp, rays, r.drive, tw, to, &bar);
      bar.finish();
    }
    for (auto& w : writes) w.get();  // rethrows a writer's failure (the temporaries are removed)
    outputs.commit();
    const double writeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tw0).count();

    for (const auto& w : r.stats.warnings) std::fprintf(stderr, "inim: warning: %s\n", w.c_str());
    if (!o->quiet) {
      std::string summary = summaryText(r.stats, s.gamut);  // warnings went to stderr already
      std::string shown;
      size_t pos = 0;
      while (pos < summary.size()) {
        size_t nl = summary.find('\n', pos);
        std::string line = summary.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos + 1);
        if (line.rfind("warning:", 0) != 0) shown += line;
        pos = nl == std::string::npos ? summary.size() : nl + 1;
      }
      std::printf("%s", shown.c_str());
      std::printf("wrote:       %s (%d x %d, %s), %s", o->out.c_str(), r.eia.width, r.eia.height,
                  s.aovs ? "R G B A Z" : "R G B", png.c_str());
      if (!o->preview.empty())
        std::printf(", %s (%d lenslets: %d real, %d virtual, %d on the MLA plane, %d missed; scene crosses the MLA "
                    "at %d)",
                    o->preview.c_str(), pv.lenslets, pv.real, pv.virtualHits, pv.onPlane, pv.missed,
                    pv.crossingLenslets);
      if (!o->sdf.empty())
        std::printf(", %s (%llu triad rays at %s/%s/%s nm)", o->sdf.c_str(), (unsigned long long)triads,
                    formatNumber(tw.nm[0]).c_str(), formatNumber(tw.nm[1]).c_str(), formatNumber(tw.nm[2]).c_str());
      double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("\ntotal:       %.2f s (loading %.2f s, synthesis %.2f s, writing %.2f s)\n", total, loadSeconds,
                  r.stats.seconds, writeSeconds);
    }
  });
}

}  // namespace inim::cli
