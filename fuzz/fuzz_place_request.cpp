// libFuzzer target: a request body of the placement page (src/place): PUT /api/state through
// applyStatePatch, then, as POST /api/write and /api/predict, the job body's keys and the output
// name, and for a refused body the error answer the server builds from its message
// (fuzz/README.md). Bodies are held in memory, as the server holds them.
#include <string>

#include "core/json_config.h"
#include "place/place_jobs.h"
#include "place/place_state.h"
#include "fuzz_input.h"

namespace {

// The keys the job bodies take, checked as PlaceJobs::submit checks them (without starting work).
void checkJobBody(const inim::Json& j) {
  if (!j.is_object()) return;
  inim::JsonObject o(j, "request body", "");
  (void)o.choice("what", {"run", "eia", "sdf"}, "run");
  (void)o.number("angle_deg", 0.0);
  (void)o.integer("width", 324);
  (void)inim::sanitizeOutputName(o.string("name", "placement"));
  o.rejectUnknown();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string body(reinterpret_cast<const char*>(data), size);
  inim::PlaceState s;
  s.display = "/displays/a.json";
  try {
    const inim::Json j = inim::parseJsonText(body, "request body");
    const inim::PlaceState t = inim::applyStatePatch(s, j, {"/displays/a.json", "/displays/b.json"});
    (void)inim::runFileJson(t, "/scenes/s.json").dump();
    (void)inim::placeStateJson(t).dump();
  } catch (const inim::InputError& e) {
    (void)inim::jsonText(inim::Json{{"error", e.what()}});  // the 400 answer, valid whatever the bytes
  }
  try {
    checkJobBody(inim::parseJsonText(body, "request body"));
  } catch (const inim::InputError& e) {
    (void)inim::jsonText(inim::Json{{"error", e.what()}});
  }
  return 0;
}
