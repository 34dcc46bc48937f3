// inim query: a field's colour along every ray of a ray table (`inim rays --for-field`), written
// as the colour table `inim eia --field-colors` reads. It is what an external NeRF does with the
// table, done by one of inim's own fields, so the exchange can be checked end to end.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/output_file.h"
#include "field_files/field_factory.h"

namespace inim::cli {

void addQueryCommand(CLI::App& app) {
  struct Opts {
    std::string field, rays, out;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "query", "Query a field along the rays of a table written by `inim rays --for-field`; writes linear Rec.709 "
               "R G B A depth per ray (.npy or .exr) for `inim eia --field-colors FILE --field-colors-encoding linear`");
  cmd->add_option("--field", o->field, "Scene JSON, trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)")->required();
  cmd->add_option("--rays", o->rays, "Ray table (.npy or .exr) from `inim rays --for-field`")->required();
  cmd->add_option("--out", o->out, "Colour table (.npy: float32 N x 5, or .exr: R G B A Z)")->required();
  addRunOptions(cmd, o->run, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string ext = std::filesystem::path(o->out).extension().string();
    if (ext != ".npy" && ext != ".exr") throw InputError("", "--out", "\"" + o->out + "\"", "a .npy or .exr table");
    const LoadedField lf = loadField(o->field, "field");
    const RayTable table = readRayTable(o->rays, 1);
    OutputSet outputs;
    writeColorTable(outputs.add(o->out), answerRayTable(*lf.field, table, o->run.seed));
    outputs.commit();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("queried %s (%s) along %zu rays of %s: %s in %.2f s\n", lf.path.c_str(), fieldKindName(lf.kind),
                table.rays.size(), o->rays.c_str(), o->out.c_str(), s);
  });
}

}  // namespace inim::cli
