// inim render: a spectral image of a field (an analytic scene by default) through a
// pinhole or thin-lens camera. Writes the linear EXR (R,G,B Rec.709, A, Z) and an sRGB PNG
// beside it.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/output_file.h"
#include "fields/field_factory.h"
#include "render/renderer.h"
#include "scene/analytic_scene.h"

namespace inim::cli {

namespace {

// "x,y,z" -> vector; InputError naming the option otherwise.
Vec3 parseVec3Option(const std::string& text, const std::string& option) {
  Vec3 v;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v.x, &v.y, &v.z, &extra) != 3 || !isFinite(v))
    throw InputError("", option, "\"" + text + "\"", "three finite numbers x,y,z");
  return v;
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  struct Opts {
    std::string scene, out, eye = "0,0,350", lookAt = "0,0,0", up = "0,1,0", integrator;
    CameraSpec cam;
    int spp = 16, maxDepth = -1;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand("render", "Render a scene spectrally through a pinhole or thin-lens camera");
  cmd->add_option("--scene,--field", o->scene,
                  "Scene JSON, or a trained radiance field (.inimrf) for novel views in its own units and frame "
                  "(default: scenes/paper-fig7.json)");
  cmd->add_option("--out", o->out, "Output EXR (linear Rec.709 + A + Z); an sRGB PNG is written beside it")
      ->required();
  cmd->add_option("--width", o->cam.width, "Image width, pixels")->capture_default_str();
  cmd->add_option("--height", o->cam.height, "Image height, pixels")->capture_default_str();
  cmd->add_option("--spp", o->spp, "Samples per pixel")->capture_default_str();
  cmd->add_option("--eye", o->eye, "Camera position x,y,z in mm (display frame)")->capture_default_str();
  cmd->add_option("--look-at", o->lookAt, "Point the camera looks at, mm")->capture_default_str();
  cmd->add_option("--up", o->up, "Up vector")->capture_default_str();
  cmd->add_option("--fov", o->cam.hfovDeg, "Horizontal field of view, degrees")->capture_default_str();
  cmd->add_option("--aperture", o->cam.apertureMm, "Thin-lens aperture diameter, mm (0 = pinhole)")
      ->capture_default_str();
  cmd->add_option("--focus", o->cam.focusDistanceMm, "Focus distance, mm (default: eye to look-at)");
  cmd->add_option("--integrator", o->integrator, "direct (default in scenes) or path (NEE + MIS)")
      ->check(CLI::IsMember({"direct", "path"}));
  cmd->add_option("--max-depth", o->maxDepth, "Maximum scattering depth (overrides the scene)");
  addRunOptions(cmd, o->run, [o] {
    if (o->spp <= 0) throw InputError("", "--spp", std::to_string(o->spp), "a positive sample count");
    if (std::filesystem::path(o->out).extension() != ".exr")
      throw InputError("", "--out", "\"" + o->out + "\"", "a file name ending in .exr");
    o->cam.pose = {parseVec3Option(o->eye, "--eye"), parseVec3Option(o->lookAt, "--look-at"),
                   parseVec3Option(o->up, "--up")};
    ThinLensCamera camera(o->cam);  // validates sizes and pose before any work

    LoadedField lf = loadField(o->scene.empty() ? defaultScenePath() : o->scene, "field");
    if (!o->integrator.empty() || o->maxDepth >= 0) {
      if (!lf.analyticScene)
        throw InputError("", o->integrator.empty() ? "--max-depth" : "--integrator", lf.path,
                         "an analytic scene (a radiance field has no integrator)");
      IntegratorSettings is = lf.analyticScene->integratorSettings();
      if (o->integrator == "direct") is.type = IntegratorSettings::Type::Direct;
      if (o->integrator == "path") is.type = IntegratorSettings::Type::Path;
      if (o->maxDepth >= 0) is.maxDepth = o->maxDepth;
      lf.analyticScene->setIntegratorSettings(is);
    }

    RenderSettings rs;
    rs.spp = o->spp;
    rs.seed = o->run.seed;
    RenderResult r = renderField(*lf.field, camera, rs);

    const std::string png = std::filesystem::path(o->out).replace_extension(".png").string();
    OutputSet outputs;
    writeImage(r.image, outputs.add(o->out));
    writeImage(encodeSRGB(r.image), outputs.add(png));
    outputs.commit();
    std::printf("rendered %s: %dx%d, %d spp, %.2f s, %.2f Mrays/s (camera rays)\n  wrote %s\n  wrote %s\n",
                lf.path.c_str(), o->cam.width, o->cam.height, o->spp, r.seconds, r.raysTraced / r.seconds * 1e-6,
                o->out.c_str(), png.c_str());
  });
}

}  // namespace inim::cli
