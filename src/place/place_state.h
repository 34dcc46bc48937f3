#pragma once
// What the placement page controls (docs/place-api.md): the placement of the field against the
// display, the VCP, the EI layout and the display file. Its JSON uses the run file's keys
// (field/placement.h), so the page's state and `inim eia --run` speak one language.
//
//   PlaceState s = initialPlaceState(field, displayPath, run);
//   PlaceState t = applyStatePatch(s, parseJsonText(body, "request body"), displays);  // InputError: 400
//   Json run = runFileJson(t, fieldPath);  // what "write run file" writes
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/json_config.h"
#include "field/placement.h"
#include "synthesis/eia_synthesis.h"

namespace inim {

struct PlaceState {
  Placement placement;
  double vcpMm = SynthesisSettings{}.vcpMm;
  std::string layout = "parallel";     // "parallel" or "toed-in"
  double viewingDistanceMm = 350.0;    // D, for the toed-in layout
  std::string display;                 // the display file (absolute)
  uint64_t revision = 0;
};

// The accepted ranges (docs/place-api.md); a value outside is a 400.
struct PlaceLimits {
  double scaleMin = 1e-6, scaleMax = 1e6;
  double rotateMaxDeg = 360.0;
  double translateMaxMm = 10000.0;
  double vcpMaxMm = 10000.0;
  double viewingDistanceMinMm = 10.0, viewingDistanceMaxMm = 100000.0;
};

Json placeStateJson(const PlaceState& s);

// `cur` with the keys of `patch` applied (any subset; "placement" may be partial). Throws
// InputError naming the key and the value for an unknown key, a wrong type, a non-finite
// number, a value out of range, or a display not in `displays`; `cur` is never changed.
PlaceState applyStatePatch(const PlaceState& cur, const Json& patch, const std::vector<std::string>& displays);

// The run file (`inim eia --run`) for the state and the field shown: absolute paths, the
// placement, the VCP and the layout.
Json runFileJson(const PlaceState& s, const std::string& fieldPath);

// The equivalent `inim eia` options (for messages and tests): --scene/--display/... flags.
std::vector<std::string> eiaArguments(const PlaceState& s, const std::string& fieldPath);

}  // namespace inim
