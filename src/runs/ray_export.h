#pragma once
// `inim rays` as a library: the display rays of a layout written as the paper's Zemax ray text
// (.txt) or inim's binary rays (.irays): every pinhole chief ray, or the real-lens rays that
// leave the refracting lenslets (src/mla_optics/real_lens_rays.h), or one EI's; a ray file converted;
// or the query rays of an EIA for an external field (src/field/ray_table.h). Errors name
// settings (out, in, ei, gap_mm) before any output.
#include <optional>
#include <string>

#include "field/placement.h"
#include "runs/display_rays.h"
#include "display/layout_override.h"
#include "synthesis/eia_synthesis.h"

namespace inim {

enum class RayFileFormat { ZemaxText, Binary, FieldTable };
// By extension: .txt, .irays, or (forField) a .npy or .exr ray table; InputError naming `key`.
RayFileFormat rayFileFormat(const std::string& path, const std::string& key, bool forField = false);

struct RayExportSettings {
  std::string out;
  std::string in;              // convert this ray file instead of generating rays
  bool zemaxMacro = false;     // text as the paper's ZPL macro wrote it (UTF-16LE, CRLF, header)
  std::string displayPath;     // "": the paper's prototype
  LayoutOverride layout;
  std::optional<double> gapMm; // generate at this panel gap instead of the generation gap
  DisplayRayChoice rays;        // the real-lens or traced chief rays instead of pinhole ones
  std::string ei;              // "K,L": only that EI, positions relative to its lens (text only)
  // The query rays of an EIA instead (field frame, reversed display rays from the VCP).
  bool forField = false;
  std::optional<Placement> placement;   // a run file's
  PlacementOverride placementOverride;  // given one by one, over that
  double vcpMm = SynthesisSettings{}.vcpMm;  // as inim eia asks them
  int spp = SynthesisSettings{}.spp;
};

struct RayExportResult {
  uint64_t count = 0;
  std::string what;   // what the rays are
  std::string notes;  // lines about real-lens rays, each ending in a newline
};

RayExportResult exportRays(const RayExportSettings& s);
// "wrote N rays to OUT: what, in S s" and the notes.
std::string exportText(const RayExportSettings& s, const RayExportResult& r, double seconds);

}  // namespace inim
