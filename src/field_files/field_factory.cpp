#include "field_files/field_factory.h"

#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "fitting/dataset_fit.h"
#include "radiance/radiance_field.h"
#include "scene/analytic_scene.h"
#include "splats/splat_field.h"
#include "splats/splat_loaders.h"
#include "splats/splat_placement.h"

namespace inim {

const char* fieldKindName(FieldKind k) {
  switch (k) {
    case FieldKind::AnalyticScene: return "analytic scene";
    case FieldKind::RadianceField: return "radiance field";
    case FieldKind::ExternalColors: return "external field colours";
    case FieldKind::GaussianSplats: return "Gaussian splats";
  }
  return "field";
}

std::string defaultScenePath() { return dataPath("scenes/paper-fig7.json"); }

LoadedField loadField(const std::string& path, const std::string& key) {
  const std::string ext = lowerExtension(path);
  LoadedField f;
  f.path = path;
  if (ext == ".json") {
    std::unique_ptr<AnalyticScene> scene = AnalyticScene::load(path);
    f.analyticScene = scene.get();
    f.field = std::move(scene);
    f.kind = FieldKind::AnalyticScene;
    return f;
  }
  if (ext == ".inimrf") {
    std::unique_ptr<RadianceField> model = RadianceField::load(path);
    f.placement = defaultPlacementFor(model->grid().metadata);
    f.field = std::move(model);
    f.kind = FieldKind::RadianceField;
    return f;
  }
  if (ext == ".ply" || ext == ".splat") {
    // A splat scene has COLMAP axes and no units: defaultSplatFrame turns it into the display
    // frame (y up, z toward the viewer) and fits its central 96 % to the panel, so the field is
    // in display millimetres like an analytic scene and carries no placement of its own.
    Gaussians g = loadGaussians(path);
    const SplatFrame frame = defaultSplatFrame(g);
    f.field = std::make_unique<SplatField>(std::move(g), frame);
    f.kind = FieldKind::GaussianSplats;
    return f;
  }
  throw InputError("", key, "\"" + path + "\"",
                   "an analytic scene (.json), a trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)");
}

LoadedField loadFieldColors(const std::string& path, int spp, size_t numQueries, ColorEncoding encoding) {
  const Point3 lo(kInfinity), hi(-kInfinity);  // unknown: the table has no geometry
  LoadedField f;
  f.field = std::make_unique<ColorTableField>(ColorTableField::load(path, spp, numQueries, encoding, lo, hi));
  f.path = path;
  f.kind = FieldKind::ExternalColors;
  return f;
}

}  // namespace inim
