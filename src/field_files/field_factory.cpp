#include "field_files/field_factory.h"

#include <algorithm>

#include "core/error.h"
#include "core/file_kinds.h"
#include "core/format.h"
#include "core/output_file.h"
#include "fitting/dataset_fit.h"
#include "radiance/radiance_field.h"
#include "scene/analytic_scene.h"
#include "splats/splat_field.h"
#include "splats/splat_loaders.h"
#include "splats/splat_placement.h"

namespace inim {

namespace {

LoadedField loadAnalyticScene(const std::string& path) {
  LoadedField f;
  std::unique_ptr<AnalyticScene> scene = AnalyticScene::load(path);
  f.analyticScene = scene.get();
  f.field = std::move(scene);
  return f;
}

LoadedField loadRadianceField(const std::string& path) {
  LoadedField f;
  std::unique_ptr<RadianceField> model = RadianceField::load(path);
  f.placement = defaultPlacementFor(model->grid().metadata);
  f.field = std::move(model);
  return f;
}

// A splat scene has COLMAP axes and no units: defaultSplatFrame turns it into the display
// frame (y up, z toward the viewer) and fits its central 96 % to the panel, so the field is in
// display millimetres like an analytic scene and carries no placement of its own.
LoadedField loadSplats(const std::string& path) {
  LoadedField f;
  Gaussians g = loadGaussians(path);
  const SplatFrame frame = defaultSplatFrame(g);
  auto splats = std::make_unique<SplatField>(std::move(g), frame);
  f.splats = splats.get();
  f.field = std::move(splats);
  return f;
}

}  // namespace

const std::vector<FieldKindInfo>& fieldKinds() {
  static const std::vector<FieldKindInfo> kinds = {
      {FieldKind::AnalyticScene, "analytic scene", "shapes, lights and spectral materials, path traced",
       {FileKind::Json}, loadAnalyticScene},
      {FieldKind::RadianceField, "radiance field", "a trained voxel radiance field, ray marched",
       {FileKind::Inimrf}, loadRadianceField},
      {FieldKind::ExternalColors, "external field colours", "the colours another renderer filled in for inim's rays",
       {FileKind::Npy, FileKind::Exr}, nullptr},
      {FieldKind::GaussianSplats, "Gaussian splats", "3D Gaussians, composited along each ray",
       {FileKind::Ply, FileKind::Splat}, loadSplats},
  };
  return kinds;
}

const char* fieldKindName(FieldKind k) { return fieldKinds()[size_t(k)].name; }

std::string defaultScenePath() { return dataPath("scenes/paper-fig7.json"); }

LoadedField loadField(const std::string& path, const std::string& key) {
  const std::optional<FileKind> file = fileKindOf(path);
  for (const FieldKindInfo& k : fieldKinds()) {
    if (!k.load || std::find(k.files.begin(), k.files.end(), file) == k.files.end()) continue;
    LoadedField f = k.load(path);
    f.path = path;
    f.kind = k.kind;
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
