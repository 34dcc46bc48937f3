#pragma once
// A placement session on the depth-ramp test scene, served on a free loopback port with a random
// token, writing into a scratch folder: what the server and live-channel tests start from.
//
//   static fixtures::ServedSession* served_;                         // in a test suite
//   served_ = new fixtures::ServedSession("place_server");           // SetUpTestSuite
//   request(served_->server.port(), ...);  served_->session.state();
#include <string>

#include "core/output_file.h"
#include "fixtures.h"
#include "place/place_server.h"
#include "place/place_session.h"

namespace fixtures {

struct ServedSession {
  explicit ServedSession(const std::string& tag) : out(tag), session(options(out)), server(session, {}) {}

  ScratchDir out;  // made first, removed last
  inim::PlaceSession session;
  inim::PlaceServer server;

 private:
  static inim::PlaceOptions options(const ScratchDir& out) {
    inim::PlaceOptions o;
    o.fieldPath = inim::dataPath("scenes/test/depth-ramp.json");
    o.outDir = out.path("out");
    return o;
  }
};

}  // namespace fixtures
