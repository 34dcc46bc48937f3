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
  addSetting(cmd, "field", o->s.fieldPath)->required();
  addSetting(cmd, "rays", o->s.raysPath)->required();
  addSetting(cmd, "out", o->s.out)->required();
  addRunOptions(cmd, o->run, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    o->run.applySeed(o->s.seed);
    const QueryRunResult r = runQuery(o->s);
    std::printf("%s", queryText(o->s, r, secondsSince(t0)).c_str());
  });
}

}  // namespace inim::cli
