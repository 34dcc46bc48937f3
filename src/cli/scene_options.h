#pragma once
// Options shared by the commands that place a field in front of the display (eia, rays
// --for-field, reference, fig11): the placement transform, and where the field comes from.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "field/field.h"
#include "synthesis/placement.h"

namespace inim::cli {

// --scale, --rotate-deg, --translate-mm.
struct PlacementArgs {
  std::string scale, rotate, translate;
  CLI::Option *scaleOpt = nullptr, *rotOpt = nullptr, *trOpt = nullptr;
};
void addPlacementOptions(CLI::App* cmd, PlacementArgs& a);
// Defaults < `base` (a run file's placement, or a trained field's own) < command line. The
// result's transform is checked (a singular placement is an InputError here, before any work).
Placement resolvePlacement(const PlacementArgs& a, const std::optional<Placement>& base);

// A field and where it came from: an analytic scene (JSON) or a trained radiance-field model.
struct LoadedField {
  std::unique_ptr<Field> field;
  std::string path;
  std::string kind;                      // "analytic scene" or "radiance field"
  std::optional<Placement> placement;    // the field's own default placement (models carry one)
};
// `path` by extension: .json = analytic scene, .inimrf = trained radiance field. InputError
// naming `key` otherwise.
LoadedField loadField(const std::string& path, const std::string& key);

}  // namespace inim::cli
