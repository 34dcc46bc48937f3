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
  auto* sceneOpt = cmd->add_option("--scene", o->scene, "Scene JSON (default: scenes/paper-fig7.json)");
  cmd->add_option("--field", o->session.fieldPath,
                  "The field to place: a scene JSON, a trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)")
      ->excludes(sceneOpt);
  cmd->add_option("--display", o->session.displayPath, "Display JSON (default: optics/displays/paper-prototype.json)");
  cmd->add_option("--run", o->session.runPath, "Run file to start from (placement, display, VCP, layout)");
  cmd->add_option("--out", o->session.outDir, "The only folder the page writes into")->capture_default_str();
  cmd->add_option("--port", o->server.port, "Port to listen on (0: a free one)")->capture_default_str()
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--host", o->server.host, "Address to listen on; anything but loopback exposes the page to the network")
      ->capture_default_str();
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
