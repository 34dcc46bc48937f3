// inim place: the paper's interactive placement step (its Fig. 4) in a browser. Starts the
// placement page's server (src/place/place_server.h) on the field and display, prints one line
// with its URL and access token, and serves until Ctrl-C. docs/place-api.md.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/interrupt.h"
#include "place/place_server.h"
#include "place/place_session.h"

namespace inim::cli {

namespace {

struct PlaceOpts {
  PlaceOptions session;
  PlaceServerOptions server;
  std::string scene;
  RunOptions runOpts;
};

}  // namespace

void addPlaceCommand(CLI::App& app) {
  auto o = std::make_shared<PlaceOpts>();
  CLI::App* cmd = &app;
  auto* sceneOpt = addSetting(cmd, "scene", o->scene);
  addSetting(cmd, "field", o->session.fieldPath)->excludes(sceneOpt);
  addSetting(cmd, "display", o->session.displayPath);
  addSetting(cmd, "run", o->session.runPath);
  addSetting(cmd, "out", o->session.outDir);
  addSetting(cmd, "port", o->server.port);
  addSetting(cmd, "host", o->server.host);
  addRunOptions(cmd, o->runOpts, [o] {
    if (!o->scene.empty()) o->session.fieldPath = o->scene;
    o->runOpts.applySeed(o->session.seed);
    PlaceSession session(o->session);
    PlaceServer server(session, o->server);
    if (!isLoopbackHost(o->server.host))
      std::fprintf(stderr, "inim: warning: --host %s listens beyond this machine; the token is the only protection\n",
                   o->server.host.c_str());
    std::printf("%s\n", server.url().c_str());
    std::fflush(stdout);
    while (!interruptSignal()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  });
}

}  // namespace inim::cli
