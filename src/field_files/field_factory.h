#pragma once
// The field factory: every kind of Field from a file, chosen by the file's extension, with
// what its users need besides the Field interface (its kind, its own default placement, the
// analytic scene's integrator). Its own stage, after the stages of the field kinds (scene,
// radiance, fitting for a model's metadata), so that they need not know each other and every
// tool that takes "a field" (eia, reference, render, query, fig11, bench) loads it one way.
//
//   LoadedField f = loadField("scenes/paper-fig7.json", "scene");
//   Placement p = resolvePlacement(f.placement, {});  // a trained model carries its own
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/file_kinds.h"
#include "field/field.h"
#include "field/placement.h"
#include "field/ray_table.h"

namespace inim {

class AnalyticScene;
class SplatField;

enum class FieldKind { AnalyticScene, RadianceField, ExternalColors, GaussianSplats };

struct LoadedField {
  std::unique_ptr<Field> field;
  std::string path;
  FieldKind kind = FieldKind::AnalyticScene;
  // The field itself when it is an analytic scene (its integrator settings can be changed),
  // else null.
  AnalyticScene* analyticScene = nullptr;
  // The field itself when it is Gaussian splats (its traversal counters), else null.
  const SplatField* splats = nullptr;
  // The field's own default placement: a trained model carries one (its units); absent for
  // analytic scenes, which are in display millimetres.
  std::optional<Placement> placement;
};

// The field kinds, in the order of FieldKind: adding a kind is a loader and a line here.
// ExternalColors has no loader of its own (loadFieldColors: it needs the run's query count).
struct FieldKindInfo {
  FieldKind kind;
  const char* name;         // "analytic scene"
  const char* description;  // one line
  std::vector<FileKind> files;
  LoadedField (*load)(const std::string& path);
};
const std::vector<FieldKindInfo>& fieldKinds();
// "analytic scene", "radiance field", "external field colours", "Gaussian splats"
const char* fieldKindName(FieldKind k);

// scenes/paper-fig7.json under the data folder: the field every tool shows by default.
std::string defaultScenePath();

// `path` by extension: .json = analytic scene, .inimrf = trained radiance field, .ply / .splat =
// Gaussian splats (splats/splat_field.h; placed in display mm by splats/splat_placement.h, so
// no placement of its own). InputError naming the setting `key` otherwise.
LoadedField loadField(const std::string& path, const std::string& key);

// The colours an external renderer filled in for the query rays of a synthesis run
// (`inim rays --for-field`): one row per query, numQueries = display rays x spp. Its extent is
// unknown, so its bounds are unbounded.
LoadedField loadFieldColors(const std::string& path, int spp, size_t numQueries, ColorEncoding encoding);

}  // namespace inim
