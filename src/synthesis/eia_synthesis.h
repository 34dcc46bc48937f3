#pragma once
// Orthoscopic elemental-image synthesis: display + field + placement + settings -> the EIA.
//
//   EiLayout L = computeLayout(display);
//   SynthesisSettings s;  s.placement = ...;  s.vcpMm = 100;  s.spp = 1;
//   SynthesisResult r = synthesizeEia(L, display.panel, field, s);
//   writeEiaExr(r.eia, r.stats.exposureUsed, "eia.exr");
//   writeImage(encodeForPanel(r.eia, display.panel.eotf), "eia.png");
//
// For every display ray (rays/pinhole_rays.h, one per EI pixel, or SynthesisSettings::displayRays,
// e.g. real-lens rays) the field is queried along the
// reversed ray from the VCP (synthesis/orthoscopic.h), `spp` times with different wavelength
// packets and light samples, and the mean radiance becomes panel drive values
// (synthesis/panel_color.h). Work is split over EIs in parallel; ray ids are display ray
// indices, so the output is bit-identical for any thread count.
//
// The EIA image covers the panel's full resolution (3840 x 1644 for the paper's prototype):
// the EIs sit where the layout puts them (EI area centred, panel pixel (panelCol0, panelRow0)
// is EIA pixel (0, 0)); pixels outside every EI are black. Channels R, G, B are linear drive
// values in [0, 1]; with `aovs`, A is the mean opacity and Z the mean display z (mm, > 0 in
// front of the MLA) of the first surface over the samples that hit one (0 where A = 0).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "display/ei_layout.h"
#include "display/panel.h"
#include "field/field.h"
#include "rays/ray_set.h"
#include "synthesis/panel_color.h"
#include "field/placement.h"

namespace inim {

// The default VCP distance: in front of everything a display of a few mm gap can show sharply
// (its depth range is a few g), and of the paper-fig7 scene (nearest point z = 29 mm).
constexpr double kDefaultVcpMm = 100.0;

struct SynthesisSettings {
  Placement placement;
  double vcpMm = kDefaultVcpMm;
  int spp = 1;                  // field samples per display ray
  uint64_t seed = 1;
  double exposure = 1.0;        // drive = exposure * native RGB (before white gains, gamut),
                                // when autoExposure is off
  bool autoExposure = true;     // pick the exposure that maps the given percentile of the
  double autoPercentile = 99.0; // brightest drive channel, over the pixels that see the
                                // scene, to full drive (1): at most 1 % of them clip
  bool whiteBalanceD65 = false; // gains so that D65 drives (1, 1, 1) (panel_color.h)
  GamutMapping gamut = GamutMapping::Clip;
  // Panel-side colour correction applied to the drive values after the gamut mapping (a
  // calibration from `inim calibrate`, read with loadCalibration); null: none.
  std::shared_ptr<const ColourModel> correction;
  bool aovs = false;            // A (opacity) and Z (display z, mm) channels
  bool progress = true;         // a bar on a terminal only
  int raysPerBatch = 4096;      // field queries per Field::query call
  // Precomputed display rays (L.numRays() of them, in ray order, origins on or near z = 0,
  // unit directions with d.z > 0), used instead of the pinhole rays: e.g. the real-lens rays
  // of mla_optics/real_lens_rays.h. Not owned; null: pinhole rays (rays/pinhole_rays.h).
  const RaySet* displayRays = nullptr;
};

// The EXR header entry that keeps SynthesisStats::exposureUsed with the EIA (`inim eia`, `inim
// fig11`), so that a later `inim view --reference` exposes its reference in the same units.
constexpr const char* kEiaExposureHeader = "inim:exposure";
// Writes an EIA so (uncompressed: its values are Monte Carlo noise to the last bit).
void writeEiaExr(const Image& eia, double exposureUsed, const std::string& path);

struct SynthesisStats {
  uint64_t displayRays = 0;
  uint64_t queries = 0;         // display rays x spp
  uint64_t hitRays = 0;         // display rays with at least one sample on a surface
  uint64_t realRays = 0;        // ... whose mean hit lies in front of the MLA (z > 0)
  uint64_t virtualRays = 0;     // ... behind it (z < 0)
  double seconds = 0.0;         // wall time of synthesizeEia
  double querySeconds = 0.0;    // of which the field queries and colour conversion
  double exposureUsed = 1.0;
  GamutStats gamut;
  // Scene bounds in the display frame (the field's bounds through the placement).
  Point3d sceneLo{0.0}, sceneHi{0.0};
  bool sceneBoundsKnown = true;  // false for colours from elsewhere (sceneLo/Hi then unset)
  bool hitDepthsKnown = true;    // false when the field gave no depth (real/virtual counts 0)
  bool sceneBehindVcp = false;  // the whole scene is closer to the viewer than the VCP
  bool sceneClipped = false;    // part of the scene lies in front of the VCP (clipped)
  bool emptyEia = false;        // no query ray hit the scene
  std::vector<std::string> warnings;  // the EIA is empty
  std::vector<std::string> notes;     // worth knowing: part of the scene clipped by the VCP
  double raysPerSecond() const { return seconds > 0 ? double(queries) / seconds : 0.0; }
};

struct SynthesisResult {
  Image eia;                 // panel resolution; R, G, B (+ A, Z with aovs)
  std::vector<float> drive;  // per display ray, in ray order: R, G, B (for triads)
  SynthesisStats stats;
};

// Throws InputError for a singular placement or bad settings (spp < 1, non-finite VCP,
// exposure <= 0, displayRays of the wrong size).
SynthesisResult synthesizeEia(const EiLayout& L, const Panel& panel, const Field& field,
                              const SynthesisSettings& s);

// The EIA pixels (L.eiaW x L.eiaH, first three channels) of a panel-resolution image, or the
// image itself when it already has the EIA size. InputError for any other size.
Image eiaArea(const EiLayout& L, const Image& img, const std::string& file = "");
// A panel-resolution image with the EIA pixels placed where the layout puts them.
Image onPanel(const EiLayout& L, const Image& eiaAreaImage);

// Drive values encoded through the panel's EOTF (RGB, [0, 1], ready for an 8-bit PNG).
Image encodeForPanel(const Image& eia, const Eotf& eotf);

// A short human-readable summary (rays, time, rays/s, hits, gamut, warnings).
std::string summaryText(const SynthesisStats& st, const GamutMapping mapping);

}  // namespace inim
