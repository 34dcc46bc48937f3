// inim query: a field's colour along every ray of a ray table; the run is src/runs/query_run.h.
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/query_run.h"

namespace inim::cli {

void addQueryCommand(CLI::App& app) {
  struct Opts {
    QueryRunSettings s;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("--field", o->s.fieldPath, "Scene JSON, trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)")->required();
  cmd->add_option("--rays", o->s.raysPath, "Ray table (.npy or .exr) from `inim rays --for-field`")->required();
  cmd->add_option("--out", o->s.out, "Colour table (.npy: float32 N x 5, or .exr: R G B A Z)")->required();
  addRunOptions(cmd, o->run, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    o->run.applySeed(o->s.seed);
    const QueryRunResult r = runQuery(o->s);
    std::printf("queried %s (%s) along %zu rays of %s: %s in %.2f s\n", r.fieldPath.c_str(), fieldKindName(r.fieldKind),
                r.rays, o->s.raysPath.c_str(), o->s.out.c_str(), secondsSince(t0));
  });
}

}  // namespace inim::cli
