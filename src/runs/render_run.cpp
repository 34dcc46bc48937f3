#include "runs/render_run.h"

#include <cstdio>
#include <filesystem>

#include "core/format.h"
#include "core/error.h"
#include "core/output_file.h"
#include "field_files/field_factory.h"
#include "scene/analytic_scene.h"

namespace inim {

Vec3 parseCameraVector(const std::string& text, const std::string& key) {
  Vec3 v;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v.x, &v.y, &v.z, &extra) != 3 || !isFinite(v))
    throw InputError("", key, "\"" + text + "\"", "three finite numbers x,y,z");
  return v;
}

RenderRunResult runRender(const RenderRunSettings& s) {
  if (s.render.spp <= 0) throw InputError("", "spp", std::to_string(s.render.spp), "a positive sample count");
  if (std::filesystem::path(s.out).extension() != ".exr")
    throw InputError("", "out", "\"" + s.out + "\"", "a file name ending in .exr");
  const FovCameraModel camera(s.camera);  // validates sizes and pose before any work
  RenderRunResult r;
  LoadedField field = loadField(s.fieldPath.empty() ? defaultScenePath() : s.fieldPath, "field");
  r.fieldPath = field.path;
  if (s.integrator || s.maxDepth) {
    if (!field.analyticScene)
      throw InputError("", s.integrator ? "integrator" : "max_depth", field.path,
                       "an analytic scene (a radiance field has no integrator)");
    IntegratorSettings is = field.analyticScene->integratorSettings();
    if (s.integrator) is.type = *s.integrator;
    if (s.maxDepth) is.maxDepth = *s.maxDepth;
    field.analyticScene->setIntegratorSettings(is);
  }
  r.render = renderField(*field.field, camera, s.render);
  r.png = std::filesystem::path(s.out).replace_extension(".png").string();
  OutputSet outputs;
  writeImage(r.render.image, outputs.add(s.out));
  writeImage(encodeSRGB(r.render.image), outputs.add(r.png));
  outputs.commit();
  return r;
}

std::string renderText(const RenderRunSettings& s, const RenderRunResult& r) {
  return formatText("rendered %s: %dx%d, %d spp, %.2f s, %.2f Mrays/s (camera rays)\n  wrote %s\n  wrote %s\n",
                    r.fieldPath.c_str(), s.camera.width, s.camera.height, s.render.spp, r.render.seconds,
                    r.render.raysTraced / r.render.seconds * 1e-6, s.out.c_str(), r.png.c_str());
}

}  // namespace inim
