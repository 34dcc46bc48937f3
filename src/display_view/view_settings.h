#pragma once
// What renderView (view_renderer.h) is asked to do: the spectral sampling, the panel estimator
// and their parameters. The defaults are the ones `inim view`, `fig11`, the studies and `bench`
// use (set nothing here unless a command-line option asks).
#include <cstdint>
#include <memory>
#include <string>

namespace inim {

class QuadratureTableCache;

// Wavelengths of the sampled estimators (docs/view-estimators.md): each primary's spectrum
// importance-sampled (Primaries), or pbrt-v4's visible 4-wavelength packet (Visible).
enum class SpectralSampling { Primaries, Visible };
const char* spectralSamplingName(SpectralSampling s);  // "primaries", "visible"

// How a pixel gathers the panel's light (src/display_view/estimators/):
//   PointSample: the subpixel under each sampled ray's landing point (the reference).
//   Footprint:   the exact average of the emitter over a box around each landing point, the
//                size of the sample's share of the pixel's footprint on the panel.
//   Quadrature:  no sampling: the pixel's area, the aperture and the primaries' spectra
//                integrated by quadrature, the pixel cut along the lenslet borders.
enum class PanelEstimator { PointSample, Footprint, Quadrature };
const char* panelEstimatorName(PanelEstimator e);  // "point", "footprint", "quadrature"
// "point", "footprint" or "quadrature" -> the estimator; false for anything else.
bool parsePanelEstimator(const std::string& name, PanelEstimator& out);

struct ViewSettings {
  int spp = 16;                   // samples (Quadrature: strata) per pixel
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
  // Tiles whose probes are all vignetted, or point away from the display, are never skipped.
  bool cullTiles = true;
  PanelEstimator panelEstimator = PanelEstimator::Quadrature;
  // Footprint: a scale on the box size (1: the box's variance is the sample's 1/spp share of the
  // variance of the pixel's landing points; 0: a point sample, on the Footprint code path).
  double footprintScale = 1.0;
  // Quadrature: the aperture table's grid (G x G cells over the exit-pupil box; ~0.8 G^2
  // points inside a round pupil) and the size, in pixels, of the blocks that share one table
  // (0: ~0.1 mm of the sensor, at most 32 px).
  int apertureGrid = 16;
  int apertureBlock = 0;
  // Quadrature: wavelength nodes per primary when something is dispersive (1: at the middle of
  // each primary's spectrum, weighted by the whole spectrum's camera RGB).
  int wavelengthNodes = 1;
  // Quadrature: aperture tables shared with other renders through the same camera
  // (estimators/quadrature_tables.h); none: this render's own.
  std::shared_ptr<QuadratureTableCache> tableCache;
};

}  // namespace inim
