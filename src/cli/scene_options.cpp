#include "cli/scene_options.h"

#include <filesystem>

#include "fitting/dataset_fit.h"
#include "core/error.h"
#include "radiance/radiance_field.h"
#include "scene/analytic_scene.h"

namespace inim::cli {

void addPlacementOptions(CLI::App* cmd, PlacementArgs& a) {
  a.scaleOpt = cmd->add_option("--scale", a.scale,
                               "Placement scale, display mm per field unit: S or sx,sy,sz (analytic scenes are in "
                               "mm: 1; the paper's NeRF at 0.0075 units/mm: 133.33)");
  a.rotOpt = cmd->add_option("--rotate-deg", a.rotate, "Placement rotation rx,ry,rz (x, then y, then z), degrees");
  a.trOpt = cmd->add_option("--translate-mm", a.translate, "Placement translation x,y,z in mm (applied last)");
}

Placement resolvePlacement(const PlacementArgs& a, const std::optional<Placement>& base) {
  Placement p = base.value_or(Placement{});
  if (a.scaleOpt && a.scaleOpt->count()) {
    p.scale = parseVec3(a.scale, "--scale", true);
    p.scaleKey = "--scale";
    p.source = "command line";
  }
  if (a.rotOpt && a.rotOpt->count()) p.rotateDeg = parseVec3(a.rotate, "--rotate-deg"), p.source = "command line";
  if (a.trOpt && a.trOpt->count()) p.translateMm = parseVec3(a.translate, "--translate-mm"), p.source = "command line";
  (void)p.toDisplay();
  return p;
}

LoadedField loadField(const std::string& path, const std::string& key) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  LoadedField f;
  f.path = path;
  if (ext == ".json") {
    f.field = AnalyticScene::load(path);
    f.kind = "analytic scene";
    return f;
  }
  if (ext == ".inimrf") {
    auto rf = RadianceField::load(path);
    f.placement = defaultPlacementFor(rf->grid().metadata);
    f.field = std::move(rf);
    f.kind = "radiance field";
    return f;
  }
  throw InputError("", key, "\"" + path + "\"", "an analytic scene (.json) or a trained radiance field (.inimrf)");
}

}  // namespace inim::cli
