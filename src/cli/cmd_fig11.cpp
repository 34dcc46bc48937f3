// inim fig11: the paper's Fig. 11 reproduced in software. One run makes the EIA of a scene for
// a display, then looks at the display and at the scene itself with the same camera from five
// directions (0 deg, +-7 deg horizontally, +-7 deg vertically, the display turned about its
// centre as the paper's gimbal does), and writes the views, a contact sheet laid out like the
// figure, and metrics.json / metrics.csv (PSNR, SSIM, CIEDE2000 mean and 95th percentile over
// the pixels that see the display; both images exposed automatically, compared as sRGB).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/contact_sheet.h"
#include "analysis/metrics.h"
#include "analysis/plot.h"
#include "camera/camera_config.h"
#include "cli/commands.h"
#include "cli/scene_options.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "scene/analytic_scene.h"
#include "synthesis/eia_synthesis.h"
#include "view/display_model.h"
#include "view/reference_renderer.h"
#include "view/view_camera.h"
#include "view/view_image.h"

namespace fs = std::filesystem;

namespace inim::cli {

namespace {

struct Fig11Pose {
  const char* name;   // file-name stem
  const char* label;  // contact-sheet label
  double rotH, rotV;
};
// Left/right: the display turned about its vertical axis; top/bottom: about its horizontal axis.
// The sign convention is view/display_pose.h's.
constexpr Fig11Pose kPoses[5] = {{"centre", "0°", 0, 0},
                                 {"left", "H -7°", -7, 0},
                                 {"right", "H +7°", 7, 0},
                                 {"top", "V +7°", 0, 7},
                                 {"bottom", "V -7°", 0, -7}};


}  // namespace

void addFig11Command(CLI::App& app) {
  struct Opts {
    std::string display, scene, camera = "alvium-1800-u-500c", out, mla = "real";
    PlacementArgs place;
    int width = 648, spp = 4, refSpp = 8, eiaSpp = 4;
    double angle = 7.0, distanceMm = 0.0;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "fig11", "Reproduce the paper's Fig. 11: EIA, five reconstructed and five reference views, contact sheet, metrics");
  cmd->add_option("--out", o->out, "Output folder")->required();
  cmd->add_option("--display", o->display, "Display JSON (default: the paper's prototype)");
  cmd->add_option("--scene,--field", o->scene,
                  "The field: a scene JSON or a trained radiance field (.inimrf) (default: scenes/paper-fig7.json)");
  cmd->add_option("--camera", o->camera, "Camera description (name in optics/cameras or a file)")->capture_default_str();
  cmd->add_option("--mla", o->mla, "MLA model for the reconstruction: real (refracting) or ideal (thin lenslets)")
      ->check(CLI::IsMember({"real", "ideal"}))
      ->capture_default_str();
  cmd->add_option("--width", o->width, "View width in pixels (the sensor's pixel pitch scales; 2592 = full)")
      ->capture_default_str();
  cmd->add_option("--spp", o->spp,
                  "Strata per pixel of the reconstructed views (quadrature estimator: deterministic, RMSE ~1% of "
                  "the mean against 16x as many at 648 px)")
      ->capture_default_str();
  cmd->add_option("--reference-spp", o->refSpp, "Samples per pixel of the reference views")->capture_default_str();
  cmd->add_option("--eia-spp", o->eiaSpp, "Field samples per display ray for the EIA")->capture_default_str();
  cmd->add_option("--angle", o->angle, "Viewing angle of the four side views, degrees")->capture_default_str();
  cmd->add_option("--distance-mm", o->distanceMm, "Camera distance (default: the camera description's)");
  addPlacementOptions(cmd, o->place);
  addRunOptions(cmd, o->run);

  cmd->callback([o]() {
    for (auto [v, key] : {std::pair{o->spp, "--spp"}, {o->refSpp, "--reference-spp"}, {o->eiaSpp, "--eia-spp"},
                          {o->width, "--width"}})
      if (v < 1) throw InputError("", key, std::to_string(v), "a whole number >= 1");
    if (!(o->angle >= 0.0 && o->angle < 60.0))
      throw InputError("", "--angle", std::to_string(o->angle), "an angle in [0, 60) degrees");
    ThreadLimit threads(o->run.threads);

    // Inputs first: every error is reported before any work or output.
    Display display = loadDisplay(displayPathOrDefault(o->display));
    EiLayout layout = computeLayout(display);
    std::string scenePath = o->scene.empty() ? defaultScenePath() : o->scene;
    LoadedField lf = loadField(scenePath, "--field");
    const Field& scene = *lf.field;
    CameraDescription desc = loadCameraDescription(o->camera);
    const Placement placement = resolvePlacement(o->place, lf.placement);
    const Transform fieldToDisplay = placement.toDisplay();
    const double distance = o->distanceMm > 0.0 ? o->distanceMm : desc.distanceMm;

    // 1. The EIA, as `inim eia` makes it.
    SynthesisSettings ss;
    ss.placement = placement;
    ss.spp = o->eiaSpp;
    ss.seed = o->run.seed;
    ss.autoExposure = true;
    SynthesisResult eia = synthesizeEia(layout, display.panel, scene, ss);
    std::printf("EIA:         %d x %d px from %s, %.2f s\n", eia.eia.width, eia.eia.height, scenePath.c_str(),
                eia.stats.seconds);
    DisplayModel dm = makeDisplayModel(display, layout, eia.eia, "(synthesized EIA)",
                                       o->mla == "ideal" ? MlaKind::Ideal : MlaKind::Real);

    // 2. Five poses: reconstruction and reference through the same camera.
    OutputSet outputs;
    const fs::path dir(o->out);
    writeImage(eia.eia, outputs.add((dir / "eia.exr").string()));
    writeImage(encodeForPanel(eia.eia, display.panel.eotf), outputs.add((dir / "eia.png").string()));
    Fig11Views sheet;
    Json metrics = Json::object();
    std::vector<std::vector<std::string>> rows;
    std::printf("%-8s %-14s %9s %7s %9s %9s %8s %8s\n", "view", "pose", "PSNR dB", "SSIM", "dE mean", "dE p95",
                "rec s", "ref s");
    for (const Fig11Pose& p : kPoses) {
      DisplayPose pose;
      pose.rotHDeg = p.rotH == 0 ? 0.0 : std::copysign(o->angle, p.rotH);
      pose.rotVDeg = p.rotV == 0 ? 0.0 : std::copysign(o->angle, p.rotV);
      pose.distanceMm = distance;
      ViewCameraOptions co;
      co.width = o->width;
      auto camera = makeViewCamera(desc, pose, co);

      ViewSettings vs;
      vs.spp = o->spp;
      vs.seed = o->run.seed;
      vs.panelEstimator = PanelEstimator::Quadrature;
      vs.apertureGrid = 16;  // the aperture table's own error ~1% (view_renderer.h)
      ViewResult rec = renderView(*camera, desc.sensor, *dm.mla, *dm.panel, dm.area, vs);
      if (!rec.stats.displayInView())
        std::fprintf(stderr, "inim: warning: the display is out of view at %s\n", pose.describe().c_str());
      ReferenceSettings rs;
      rs.spp = o->refSpp;
      rs.seed = o->run.seed;
      ViewResult ref = renderReference(scene, fieldToDisplay, *camera, desc.sensor, rs);

      // One exposure for both, in the same units: the EIA maps field luminance Y to drive
      // exposureUsed x Y, which the panel shows at exposureUsed x Y x peak luminance (cd/m^2), the
      // unit of the reconstruction. So the reference, scaled by that, is what an ideal display
      // would show; the exposure that suits the reference then applies to both, and what the
      // optics lose or add (Fresnel, black matrix, crosstalk) stays visible in the metrics.
      const Image refCdM2 = scaledImage(ref.image, eia.stats.exposureUsed * display.panel.peakLuminanceCdM2);
      Exposure autoExposure;
      const double k = exposureFactor(refCdM2, desc.sensor, autoExposure);
      Image recExposed = scaledImage(rec.image, k);
      Image refExposed = scaledImage(refCdM2, k);
      Image recSrgb = cameraRgbToSrgb(recExposed, desc.sensor);
      Image refSrgb = cameraRgbToSrgb(refExposed, desc.sensor);
      const std::string stem = p.name;
      writeImage(recExposed, outputs.add((dir / ("view_" + stem + ".exr")).string()));
      writeImage(recSrgb, outputs.add((dir / ("view_" + stem + ".png")).string()));
      writeImage(refExposed, outputs.add((dir / ("reference_" + stem + ".exr")).string()));
      writeImage(refSrgb, outputs.add((dir / ("reference_" + stem + ".png")).string()));

      CompareOptions copt;
      copt.spaceA = copt.spaceB = "srgb";
      const PixelMask mask = displayMask(*camera, dm.area);
      if (mask.count() == 0) {
        std::fprintf(stderr, "inim: warning: the display is out of view at %s; no metrics\n", pose.describe().c_str());
        continue;
      }
      ImageMetrics m = compareImages(refSrgb, recSrgb, copt, &mask, "reference_" + stem, "view_" + stem);
      Json mj = metricsJson(m);
      mj["rot_h_deg"] = pose.rotHDeg;
      mj["rot_v_deg"] = pose.rotVDeg;
      mj["reconstruction_seconds"] = rec.stats.seconds;
      metrics[stem] = mj;
      rows.push_back(metricsCsvRow(stem, m));
      std::printf("%-8s %-14s %9s %7.4f %9.3f %9.3f %8.1f %8.1f\n", stem.c_str(), p.label, formatPsnr(m.psnrDb).c_str(),
                  m.ssim, m.deltaE.mean, m.deltaE.p95, rec.stats.seconds, ref.stats.seconds);
      ViewPair pair{p.label, refSrgb, recSrgb};
      if (stem == "centre") sheet.centre = pair;
      if (stem == "left") sheet.left = pair;
      if (stem == "right") sheet.right = pair;
      if (stem == "top") sheet.top = pair;
      if (stem == "bottom") sheet.bottom = pair;
    }
    ContactSheetOptions cso;
    cso.heading = "inim fig11: " + fs::path(scenePath).filename().string() + " on " + display.name + ", " +
                  desc.name + " at " + std::to_string(int(std::lround(distance))) + " mm, MLA " + o->mla;
    writeImage(composeFig11Sheet(sheet, cso), outputs.add((dir / "contact_sheet.png").string()));
    {
      std::string tmp = outputs.add((dir / "metrics.json").string());
      FILE* f = std::fopen(tmp.c_str(), "w");
      if (!f) throw std::runtime_error("cannot write " + tmp);
      std::fputs(metrics.dump(2).c_str(), f);
      std::fputc('\n', f);
      std::fclose(f);
    }
    writeCsv(outputs.add((dir / "metrics.csv").string()), metricsCsvHeader("view"), rows);
    outputs.commit();
    std::printf("wrote:       %s/{eia.exr,eia.png,view_*.exr|png,reference_*.exr|png,contact_sheet.png,metrics.json,metrics.csv}\n",
                o->out.c_str());
  });
}

}  // namespace inim::cli
