#pragma once
// inim's speed benchmarks on Google Benchmark, with ratios taken between benchmarks of the
// same run (these machines are shared and noisy, so absolute times drift):
//
//   render/paper-fig7      the full default render (1920x1080, 16 spp, direct lighting)
//   query/bare-embree      rtcIntersect1 over the camera rays of that image, nothing else
//   query/inim-hit         the same rays through inim's intersection (full surface data)
//   query/inim-field       the same rays through Field::query (radiance, direct lighting)
//   eia/paper-fig7         full orthoscopic EIA of the default display (6,215,625 rays, 1 spp)
//   eia-query/bare-embree  rtcIntersect1 over that EIA's 6.2M query rays
//   eia-query/inim-field   the same query rays through Field::query
//   view/E/spp:N           a view of the default EIA (real MLA, real lens, 0 deg) at the view
//                          width, N spp, panel estimator E (point, footprint, quadrature);
//                          view/reference/E is the same estimator at the reference spp (seed 2).
//                          The table after the run gives each one's RMSE against its own
//                          reference (noise) and against the point estimator's reference
//                          (noise + bias), relative to the reference's mean, and the ratio of
//                          the means
//   reference/E/spp:N      the reference view of the default scene (real lens, 0 deg, 324 px) at
//                          N spp with the direct integrator's light sampling E (all-lights: each
//                          light at every sample, the default scene's; one-light: one picked by
//                          power); the table after the run gives each one's RMSE against a
//                          1024-spp reference rendered once (the reference cache) and its
//                          efficiency, relative MSE x seconds
//   radiance/eia-query     the default display's EIA from a trained model (when one is given);
//                          target <= 30 s on 2 cores
//   place/level0-update/F  the placement page's server: a change of state to its level-0
//                          preview ready (one ray per lenslet, PNG), for the default scene, the
//                          shipped splats and a trained model (when one is given); target
//                          <= 100 ms on 2 cores
//   scene/load-spheres/N   a scene description of N spheres parsed and read (10k, 100k, 1M):
//                          linear in N; target: 1M in seconds
//   scene/load-rectangles/100000  the same for emissive rectangles (meshes): linear too
//   mla/real-one-layer, mla/stack-one-layer, mla/stack-two-layers  camera rays to the panel
//                          through the default MLA (exact tracer; stack tracer) and a two-layer
//                          stack; ratios against the first; target: two layers within 2x
//   lens/read-zmx-30-surfaces+schott  a 30-surface .zmx lens and the SCHOTT catalogue read;
//                          target < 50 ms together
//   lens/trace-even-asphere, lens/trace-spherical  rays through the AL2520-A asphere and through
//                          it made spherical; target: the asphere within 1.3x
//   radiance/train-lego    train on the Lego scene (when its folder is given) at 200 x 200, every
//                          8th view held out; reports the held-out PSNR; target >= 28 dB within
//                          10 minutes
#include <string>
#include <vector>

#include "field/placement.h"
#include "display_view/view_renderer.h"

namespace inim {

struct ViewBenchSettings {
  int width = 648;                   // image width (2592 = the sensor)
  std::vector<int> spps = {1, 4, 16};
  std::vector<PanelEstimator> estimators = {PanelEstimator::PointSample, PanelEstimator::Footprint,
                                            PanelEstimator::Quadrature};
  int referenceSpp = 0;                       // 0: 16x the largest of spps
  int grid = ViewSettings{}.apertureGrid;     // aperture table grid of the runs
  int referenceGrid = 0;                      // ... of their references; 0: grid
};

struct RadianceBenchSettings {
  std::string modelPath;       // radiance/eia-query runs when given (.inimrf)
  PlacementOverride placement;  // over the model's own placement
  std::string legoDir;         // radiance/train-lego runs when given
  int legoIterations = 3000;
};

struct BenchSettings {
  std::string filter = ".*";  // regex of the benchmarks to run
  double minTime = 0.5;       // minimum seconds per repeated benchmark
  int threads = 0;            // as limited by the caller (0: all cores); printed in the header
  ViewBenchSettings view;
  RadianceBenchSettings radiance;
};

// Registers the benchmarks, runs those the filter selects, and prints the results and the
// tables of ratios to stdout.
void runBenchmarks(const BenchSettings& settings);

}  // namespace inim
