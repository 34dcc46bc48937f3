#pragma once
// What a camera sees when the display shows an EIA (DESIGN.md section 1, step 6; issue 4
// item 4): spectral Monte Carlo, traced backwards from the sensor.
//
//   auto cam = makeViewCamera(desc, pose, {});                     // rays in the display frame
//   DisplayModel dm = makeDisplayModel(display, layout, eia, "eia.exr", MlaKind::Real);
//   ViewResult r = renderView(*cam, desc.sensor, *dm.mla, *dm.panel, dm.area, settings);
//
// Per pixel and sample: a pixel position and a lens position (Owen-scrambled Sobol, qmc.h)
// -> camera ray (display frame) -> does it reach the MLA's front plane inside the display's
// active area? (no: it sees the background, a D65 grey of luminance backgroundY, camera RGB
// (Y, Y, Y)) -> MlaModel::traceToPanel -> PanelEmitter -> camera weight x MLA throughput x
// emitted radiance x the sensor's white-balanced response, divided by the wavelength pdf.
// Rays that the MLA reflects back or loses see nothing (the room is dark).
//
// Wavelengths (both strategies are unbiased; tests check that they agree):
//   Primaries (default): the panel emits only its three primaries, so the measurement splits
//     into one term per primary. The wavelength of the term for primary c is importance-
//     sampled from that primary's own spectrum (a 1 nm piecewise-constant pdf, exact ratio
//     spectrum/pdf in the weight).
//       - Nothing wavelength dependent (camera, MLA and cover glass non-dispersive): one ray
//         per sample carries every wavelength; whichever subpixel it lands on contributes that
//         primary's exact spectral integral, weight x integral(K_c L0 primary_c x response).
//         No spectral noise at all.
//       - Something dispersive: one ray per primary per sample (3 rays), each traced at its own
//         wavelength; ray c counts only where it lands on a subpixel of channel c (the camera
//         ray is shared by the three when the camera itself is not dispersive).
//   Visible: pbrt-v4's 4-wavelength packet from SampledWavelengths::sampleVisible; one ray
//     carries all four when nothing is dispersive, else one ray per wavelength (4 rays, each
//     weighted 1/4): a separate ray per wavelength rather than terminating the secondaries, so
//     no wavelength is wasted. Slower to converge for narrow-band primaries; kept as the
//     reference estimator.
// Output: linear, white-balanced camera RGB (a D65 grey of luminance Y gives (Y, Y, Y)); with
// the emitter in absolute units that is cd/m^2 of the equivalent D65 grey.
//
// Panel estimator (ViewSettings::panelEstimator):
//   PointSample (the reference): the subpixel under the ray's landing point. At the camera's
//     full resolution and 350 mm a pixel's lens aperture spreads, through a lenslet, over
//     ~35 um of the panel (several 13 um subpixels of different colours) and the pixel itself
//     over ~one subpixel width, so each ray is a lottery between its primary's subpixels, the
//     other primaries' and the black matrix: RMSE ~300% of the mean at 1 spp, falling as
//     1/sqrt(spp) (a little faster with the Sobol points).
//   Footprint (default): tracing through the camera lens and the MLA is the expensive part,
//     so once a ray reaches the panel it reads the EXACT average of the emitter over a box
//     around its landing point (PanelEmitter::boxAveragePx: rectangle overlaps for stripes,
//     polygons clipped to the box otherwise), per channel: every subpixel the box touches
//     contributes, weighted by its area inside the box. The box is this sample's share of the
//     pixel's footprint on the panel: per pixel, the 2 x 4 Jacobian J of the landing point
//     (panel pixels) with respect to the sample coordinates (pixel x, y; lens sample u, v) is
//     measured by one-sided finite differences (5 probe rays at the reference wavelength from
//     the pixel centre and the lens centre; steps taken toward the side that stays in the
//     same lenslet, a column that cannot be measured is 0), and the box's half-widths are
//         h_u = 0.5 s |J_u.| / sqrt(spp),  h_v = 0.5 s |J_v.| / sqrt(spp)
//     (s = footprintScale, default 1; capped at 8 panel pixels): a box whose variance is the
//     sample's 1/spp share of the variance of the pixel's landing points (uniform sample
//     coordinates, box of the lens sample square). In expectation the image is the true one
//     with the panel-side blur of each pixel widened by ~sqrt(1 + s^2/spp) (its footprint
//     convolved with the box), so the estimator is consistent: the bias goes to 0 as spp grows
//     (tests/view/test_footprint.cpp checks it against PointSample at high spp), and s = 0 is
//     PointSample bit for bit. Subpixel structure that the camera resolves, defocus and
//     braiding stay: the box only spans the sample's own share of what the pixel sees, never a
//     fixed blur. Cost: 5 probe rays per pixel (on the dispersive default, 3 rays per sample,
//     that is ~1.7 spp: 2.5x the point estimator's time at 1 spp, 1.2x at 16) plus a cheap box
//     integral per ray.
//     Measured (`inim bench --filter '^view/'`, default display and camera, 648 x 486): RMSE
//     against a 256-spp footprint image 126% / 56% / 40% at 1 / 4 / 16 spp, against 314% /
//     153% / 74% for PointSample; equal error costs ~2x (1 spp) to ~4.6x (4 spp) less time.
//     The gain shrinks as spp grows (the box shrinks with it; at 4096 spp both estimators have
//     the same noise), and the error falls more slowly than 1/sqrt(spp). What is left is the
//     noise that no panel filter removes: which lenslet a ray goes through (a pixel straddling
//     a lenslet border sees two unrelated EIs), the MLA's stochastic Fresnel choices (a few %
//     of rays reflect and see nothing), and the colour lottery inside a box narrower than a
//     pixel period. The full-resolution goal (RMSE <= 2% in 60 s) is NOT reached by this
//     estimator: at 2592 x 1944 it gives ~65% at 4 spp (~70 s on 2 shared cores).
//
// Determinism: every pixel's samples depend on (seed, pixel index, sample index) only
// (Rng::forSample seeds the Sobol scrambles and the MLA's Fresnel choices; the Footprint
// probes have their own per-pixel stream, and a pixel whose probes fail reuses the last
// Jacobian of its own tile, which one thread renders in a fixed order), so the image is
// bit-identical for any thread count. Parallel over 16 x 16 tiles; no allocation per ray.
#include <cstdint>

#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/image.h"
#include "display/ei_layout.h"
#include "mla/mla_model.h"
#include "view/panel_emitter.h"

namespace inim {

enum class SpectralSampling { Primaries, Visible };
const char* spectralSamplingName(SpectralSampling s);

// How a ray that reached the panel reads the emitter (see the header comment).
//   PointSample: the subpixel under the landing point (the reference estimator).
//   Footprint:   the exact average of the emitter over a box around the landing point, the
//                size of this sample's share of the pixel's footprint on the panel (default).
enum class PanelEstimator { PointSample, Footprint };
const char* panelEstimatorName(PanelEstimator e);  // "point", "footprint"

// The display's active area on the MLA's front plane (display frame, mm).
struct DisplayArea {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};
// The lenslet array: K x L cells of pitch P about the layout's physical lens centres.
DisplayArea lensletArrayArea(const EiLayout& layout, double pitchMm);

// Fraction of a grid x grid set of pixel centres whose central ray (lens sample at the pupil's
// centre, 550 nm) reaches the plane z = 0 inside `area`: 0 means the display is out of view.
double displayCoverage(const CameraModel& camera, const DisplayArea& area, int grid = 32);

struct ViewSettings {
  int spp = 16;
  uint64_t seed = 1;
  bool progress = true;           // a bar on a terminal only
  double backgroundY = 0.0;       // luminance of the (D65 grey) background; default black
  SpectralSampling spectral = SpectralSampling::Primaries;
  double referenceLambdaNm = 550.0;  // the wavelength non-dispersive rays are traced at
  // Diagnostics: trace one ray per primary / wavelength even when nothing is dispersive (the
  // dispersive code path on a non-dispersive setup; the expected value is the same).
  bool perWavelengthRays = false;
  // With a black background, skip 16 x 16 tiles that cannot see the display: probe rays from
  // the tile's corners and centre through a 3 x 3 grid of lens positions (at 450, 550 and
  // 650 nm for a dispersive camera) cross the MLA front plane in a box; the tile is skipped
  // (left exactly 0) when that box, grown by half its size plus 1 mm, misses the active area.
  // The box of a tile's whole ray bundle is the probes' box up to the lens's tiny
  // nonlinearity, so the margin makes this exact in practice (tests compare with and without).
  // Tiles whose probes are all vignetted, or point away from the display, are never skipped.
  bool cullTiles = true;
  // The panel estimator and, for Footprint, a scale on the box size (1: the box's variance
  // matches the sample's share, 1/spp, of the variance of the pixel's landing points; 0: a
  // point sample again, on the Footprint code path).
  PanelEstimator panelEstimator = PanelEstimator::Footprint;
  double footprintScale = 1.0;
};

struct ViewStats {
  uint64_t tracedRays = 0;   // camera rays traced (weight > 0; one per primary / wavelength when dispersive)
  uint64_t displayRays = 0;  // ... that reached the MLA inside the active area
  uint64_t panelRays = 0;    // ... that reached the panel (MLA did not lose them)
  uint64_t emittingRays = 0; // ... that landed on a subpixel (not the black matrix)
  uint64_t culledPixels = 0; // pixels of tiles that cannot see the display (left 0)
  uint64_t probeRays = 0;    // Footprint: rays traced to measure the pixels' Jacobians
  uint64_t probeFailures = 0;// Footprint: Jacobian columns that no probe could measure (set to 0)
  int raysPerSample = 1;     // 1, 3 (primaries, dispersive) or 4 (visible, dispersive)
  bool dispersive = false;
  double seconds = 0.0;
  bool displayInView() const { return displayRays > 0; }
};

struct ViewResult {
  Image image;  // R, G, B: linear white-balanced camera RGB, unexposed
  ViewStats stats;
};

// InputError for spp < 1 or a non-finite / negative background.
ViewResult renderView(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                      const PanelEmitter& panel, const DisplayArea& area, const ViewSettings& s);

}  // namespace inim
