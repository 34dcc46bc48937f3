#include "fields/field_factory.h"

#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "fitting/dataset_fit.h"
#include "radiance/radiance_field.h"
#include "scene/analytic_scene.h"

namespace inim {

const char* fieldKindName(FieldKind k) {
  switch (k) {
    case FieldKind::AnalyticScene: return "analytic scene";
    case FieldKind::RadianceField: return "radiance field";
    case FieldKind::ExternalColors: return "external field colours";
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
  throw InputError("", key, "\"" + path + "\"", "an analytic scene (.json) or a trained radiance field (.inimrf)");
}

LoadedField loadFieldColors(const std::string& path, int spp, size_t numQueries, ColorEncoding encoding) {
  const Point3 lo(-1e6f), hi(1e6f);
  LoadedField f;
  f.field = std::make_unique<ColorTableField>(ColorTableField::load(path, spp, numQueries, encoding, lo, hi));
  f.path = path;
  f.kind = FieldKind::ExternalColors;
  return f;
}

}  // namespace inim
