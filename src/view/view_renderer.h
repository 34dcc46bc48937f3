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
//   Aperture (src/view/aperture_kernel.h): the camera is focused on the display, so all the
//     rays of one pixel sample through the lens aperture meet the MLA in a spot of a few um,
//     and inside the lenslet their DIRECTION maps to the panel position: the aperture images
//     to a ~35 um disk on the panel (several subpixels: the point estimator's colour lottery).
//     This estimator integrates that disk by quadrature instead of sampling it:
//       - per block of pixels (~0.1 mm of the sensor, <= 32 px), a table of the aperture at the
//         block's centre pixel: the camera weight on a G x G grid of cells (apertureGrid, 12)
//         over the exit-pupil box (real lens: rear-vertex-plane coordinates, as the camera
//         samples them; thin lens: the lens disk), boundary cells refined 4 x 4, and for each
//         point its camera ray's offsets (crossing point on the MLA front plane, slope) from the
//         centre ray. The camera lens's own non-linearity is kept; only the MLA is linearised.
//       - per tile and lenslet: the MLA's 2 x 2 Jacobians of the landing point (panel px) with
//         respect to the crossing point and the slope, by central differences (1 camera ray,
//         8 MLA-only rays) at the first sample through that lenslet; each table point becomes
//         a panel offset.
//       - per sample: the pixel position is jittered (Sobol) as before; one ray through the
//         aperture's centroid (per primary when dispersive) traced through the MLA with Fresnel
//         as a deterministic transmittance (RealMla's Weighted mode: no random reflection)
//         gives the landing point; the estimate is (camera weight / table's centre weight) x
//         T x angular factor x sum_i w_i drive(landing + offset_i + shift), the lookup per
//         channel (PanelEmitter::channelDrivePx), with the whole kernel shifted by a random
//         sub-cell offset (the Sobol lens dimensions) so the quadrature is randomised.
//       - fallback to sampling the aperture (the point estimator, stochastic Fresnel) for a ray
//         whose centre ray misses the display or the MLA loses it, or whose lenslet's Jacobian
//         cannot be measured (probes straddling a lenslet border); counted in ViewStats.
//     Biases (the ray-by-ray quadrature test and the agreement tests measure them): the dropped
//     Fresnel ghost branch (paths with >= 2 reflections inside the MLA that still reach the
//     panel: 0.17% of the energy on the test MLA); the table's energy at G = 12 (-0.3 to +0.3%
//     against Monte Carlo over the lens; 0.5% at G = 8); the quadrature at the pupil's edge
//     (whole-cell shifts; ~1-2% of a pixel's value per channel at G = 12, 0.5% at G = 32); the
//     table and Jacobians taken at the block centre and the lenslet's first sample (the kernel's
//     shape, not its energy). Measured means: 0.996-0.997 of the point estimator (thin lens,
//     small real MLA), 0.994 (default real lens at 200 mm); block means within 2.5%.
//     It does NOT remove the lottery between lenslets: a pixel straddling a lenslet border
//     still samples which EI each jittered sample sees (at 2592 px ~13% of the display's
//     pixels, at 648 px about half), which dominates its remaining error.
//     Cost per pixel sample: the point estimator's rays (one camera + one MLA ray per primary)
//     plus ~3 x 90 channel lookups; per block ~700 camera rays; per tile and lenslet 9 rays.
//     Measured (`inim bench --filter '^view/'`, default display and camera, shared 2-core
//     machine, load 4-5; RMSE relative to the mean):
//       648 x 486, against the same estimator at 64 spp (same seed: shares samples, so these
//       underestimate): point 311% / 150% at 1 / 4 spp (0.6 / 2.2 s), footprint 127% / 58%
//       (1.7 / 3.5 s), aperture 79% / 32% (3.1 / 6.9 s). At this width a pixel covers ~1/4 of a
//       lenslet and about half the pixels straddle a lenslet border, so per unit of time the
//       footprint estimator is as good or better.
//       2592 x 1944, against the same estimator at 8 spp with another seed (includes the
//       reference's own noise): aperture 55% / 29% at 1 / 2 spp (21 / 38 s); footprint 141% /
//       104% (25 / 33 s): at full resolution ~3.5x lower error for the same time.
//       `inim view --spp 3 --estimator aperture` at full resolution: 30 s wall, peak RSS
//       0.49 GB. The goal (RMSE <= 2% in 60 s) is NOT reached: ~6 spp fit in 60 s.
//       Superseded by Quadrature (below), which also integrates the pixel's area and is the
//       default of `inim view` and `inim fig11`; kept as a sampled comparison.
//
//   Quadrature (no sampling at all): the measurement of a pixel is an integral over its area,
//     the camera's aperture and each primary's spectrum, and every one of them is done by a
//     deterministic rule, so there is no noise, only a quadrature error that falls with spp:
//       - area: the pixel is cut into spp strata (nx x ny, nx ny = spp); each stratum is cut
//         along the display's edge and the lenslet borders (MlaModel::lensletCell, at the depth
//         where neighbouring caps meet, cellBorderDepth), the borders being mapped back to the
//         sensor through the block's affine camera model (centre ray and its Jacobians per
//         ~0.1 mm block: exact to far below a pixel), per primary for a dispersive camera, whose
//         lateral colour moves the borders by a fraction of a pixel toward the field's edge;
//       - each piece (one per lenslet it sees) is integrated through its own lenslet: its
//         centroid's centre ray is traced through the MLA at each primary's wavelength node
//         (Fresnel as a transmittance), and the lenslet's map about that ray is measured by
//         MLA-only probes at the same wavelength (the pixel Jacobian changes by ~6% between
//         blue and green: A = 1 - g/f is a small difference): the secant over the piece gives
//         the size of its image on the panel and the curvature the shift of its mean;
//       - aperture: the quadrature table of ApertureKernel (G x G cells over the exit pupil),
//         its points mapped to panel offsets through the piece's own Jacobians; each point
//         reads the exact average of its channel's subpixels (PanelEmitter::channelBoxAveragePx)
//         over a box with the variance of the piece's image, so the pixel's area is integrated
//         exactly for an affine map and an axis-aligned image (the image is a parallelogram: a
//         few % shear near the lenslet corners);
//       - spectrum: wavelengthNodes nodes per primary (default 1: the median of its spectrum,
//         weighted by the whole spectrum's exact camera RGB). The nodes are not tied to strata:
//         tying a colour to a position inside the pixel is a bias that strata never remove.
//     Biases (tests/view/test_quadrature.cpp against the point estimator at 4096 spp): the
//     dropped Fresnel ghosts (0.17%), the aperture table (G = 16: ~1% at the sensor's
//     resolution), the box for a sheared image; 16 spp is within the point reference's own
//     noise (1.8%) pixel by pixel on the small real
//     setup, whose pixels cover a quarter of a lenslet. Cost per piece and primary: 1 + 4 MLA
//     rays (landing, pixel Jacobian) plus 2 per stratum (slope Jacobian), no camera-lens rays,
//     and one box average per table point (~0.8 G^2).
//     Measured (`inim bench --filter '^view/' --view-width W --view-estimators ...`, default
//     display, EIA and camera, 2 cores; RMSE relative to the mean against the same estimator at
//     16x the spp):
//       2592 x 1944 (--view-spp 1,2 --view-ref-spp 16), G = 16: 1.23% at 1 spp in 25.5 s, 0.93%
//       at 2 spp in 46 s (G = 12: 1.28% in 20 s, 0.97% in 36 s); the table's own error on top
//       (apertureGrid above) 0.94% at G = 16; `inim view` at full resolution: 27 s wall, peak
//       RSS 0.50 GB.
//       648 x 486 (--view-spp 1,4), G = 12: 2.42% / 0.75% at 1 / 4 spp (2.4 / 5.9 s), against
//       footprint 127% / 59% (0.8 / 1.6 s) and aperture 69% / 25% (1.2 / 2.9 s).
//
// Determinism: every pixel's samples depend on (seed, pixel index, sample index) only
// (Rng::forSample seeds the Sobol scrambles and the MLA's Fresnel choices; the Footprint
// probes have their own per-pixel stream, and a pixel whose probes fail reuses the last
// Jacobian of its own tile, which one thread renders in a fixed order; the Aperture tables are
// per block, built in a separate pass, and its MLA Jacobians are cached per tile, in the
// tile's fixed order; Quadrature has no random numbers and caches only per tile), so the image
// is bit-identical for any thread count. Parallel over 16 x 16 tiles; no allocation per ray.
#include <cstdint>
#include <string>

#include "analysis/metrics.h"
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
//   Aperture:    the camera aperture integrated by quadrature through an affine model of the
//                MLA (see the header comment); point sampling where the model does not hold.
//   Quadrature:  no sampling at all: the pixel's area, the aperture and the primaries' spectra
//                integrated by quadrature, the pixel cut along the lenslet borders (see the
//                header comment).
enum class PanelEstimator { PointSample, Footprint, Aperture, Quadrature };
const char* panelEstimatorName(PanelEstimator e);  // "point", "footprint", "aperture", "quadrature"
// "point", "footprint", "aperture" or "quadrature" -> the estimator; false for anything else.
bool parsePanelEstimator(const std::string& name, PanelEstimator& out);

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
// The pixels whose central ray (lens centre, 550 nm) meets the MLA plane inside `area`: where
// the display can show anything, so where reconstructions and references are compared.
PixelMask displayMask(const CameraModel& camera, const DisplayArea& area);

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
  PanelEstimator panelEstimator = PanelEstimator::Quadrature;
  double footprintScale = 1.0;
  // Aperture and Quadrature: the aperture quadrature grid (G x G cells over the exit-pupil box;
  // ~0.8 G^2 points inside a round pupil) and the size, in pixels, of the blocks that share one
  // table (0: ~0.1 mm of the sensor, at most 32 px: 32 px at 2592 wide, 11 px at 648). The
  // table's own error at the sensor's resolution (quadrature, 1 spp): 0.94% at G = 16 (against
  // 32), 1.75% at G = 12 (against 24); `inim view`, `fig11` and `bench` use 16, for 1.3x the
  // time of 12 (the tests' tolerances are stated at 12).
  int apertureGrid = 16;
  int apertureBlock = 0;
  // Quadrature: wavelength nodes per primary when something is dispersive (each piece is traced
  // once per primary and node; 1: at the middle of each primary's spectrum, weighted by the
  // whole spectrum's camera RGB).
  int wavelengthNodes = 1;
};

struct ViewStats {
  uint64_t tracedRays = 0;   // camera rays traced (weight > 0; one per primary / wavelength when dispersive)
  uint64_t displayRays = 0;  // ... that reached the MLA inside the active area
  uint64_t panelRays = 0;    // ... that reached the panel (MLA did not lose them)
  uint64_t emittingRays = 0; // ... that landed on a subpixel (not the black matrix)
  uint64_t culledPixels = 0; // pixels of tiles that cannot see the display (left 0)
  uint64_t probeRays = 0;    // Footprint: rays traced to measure the pixels' Jacobians
  uint64_t probeFailures = 0;// Footprint: Jacobian columns that no probe could measure (set to 0)
  uint64_t apertureRays = 0;     // Aperture: rays traced to build the quadrature tables and Jacobians
  uint64_t apertureSamples = 0;  // Aperture: rays (sample x primary) integrated over the aperture
  uint64_t apertureFallbacks = 0;// Aperture: rays on the display that fell back to sampling the aperture
                                 // (Quadrature: pixel strata that fell back to it)
  uint64_t quadratureParts = 0;  // Quadrature: pieces of pixel strata integrated (one per lenslet seen)
  uint64_t splitStrata = 0;      // Quadrature: strata cut into >= 2 pieces by a lenslet border
  uint64_t lostParts = 0;        // Quadrature: piece x primary whose centre ray the MLA lost (counted 0)
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
