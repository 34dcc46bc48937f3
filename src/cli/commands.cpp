#include "cli/commands.h"

#include <algorithm>

#include "core/format.h"

namespace inim::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"render", "Render a scene spectrally through a pinhole or thin-lens camera", addRenderCommand},
      {"display", "Display descriptions (optics/displays/*.json)", addDisplayCommand},
      {"rays", "Write the display rays: one pinhole chief ray per EI pixel (origin on the pinhole, z = 0; unit direction toward the viewer), in the paper's ray order", addRaysCommand},
      {"eia", "Orthoscopic EIA synthesis: query the scene along every reversed display ray from the VCP and write the panel drive values", addEiaCommand},
      {"place", "Place a scene or a trained field on the display interactively, in a browser: a local web server with live previews that writes the run file, the EIA and the SDF", addPlaceCommand},
      {"triads", "RGB-wavelength triads: Zemax SDF export and EIA formation", addTriadsCommand},
      {"view", "Simulate what a camera sees when the display shows an EIA: spectral Monte Carlo through the camera lens, the MLA and the panel's subpixels", addViewCommand},
      {"reference", "Render the scene itself through the viewing camera at the same pose, placed as for the EIA (the reference for inim view)", addReferenceCommand},
      {"fig11", "Reproduce the paper's Fig. 11: EIA, five reconstructed and five reference views, contact sheet, metrics", addFig11Command},
      {"calibrate", "Colour calibration through the simulated chain: characterise, find where the error comes from, fit, verify on hold-out colours, export .cube/CLF/OCIO", addCalibrateCommand},
      {"study", "Run a validation study: report.md, plots and CSV data in --out", addStudyCommand},
      {"query", "Query a field along the rays of a table written by `inim rays --for-field`; writes linear Rec.709 R G B A depth per ray (.npy or .exr) for `inim eia --field-colors FILE --field-colors-encoding linear`", addQueryCommand},
      {"capture", "Render a posed dataset of an analytic scene from a cap of camera positions in front of it (transforms.json + sRGB PNGs with alpha), for inim train or any NeRF tool", addCaptureCommand},
      {"train", "Train a voxel-grid radiance field (density + spherical-harmonic colour, Adam, TV, coarse to fine) from a posed photo dataset, on the CPU", addTrainCommand},
      {"eval", "Held-out PSNR and SSIM of a trained radiance field, and its rendered views", addEvalCommand},
      {"compare", "Image metrics of A against B: PSNR, SSIM (Wang et al. 2004, 11x11 Gaussian, sigma 1.5) and CIEDE2000 (mean, 95th percentile, max)", addCompareCommand},
      {"lens", "Camera lens prescriptions (optics/lenses/*.json, *.zmx, *.dat)", addLensCommand},
      {"sweep", "Design sweeps: vary display, MLA, panel, placement or run settings over a grid, run every point (locally or as a Slurm job array) and report the best design and its tolerances", addSweepCommand},
      {"bench", "Speed benchmarks (Google Benchmark) with ratios measured in one run", addBenchCommand},
  };
  return table;
}

void addCommands(CLI::App& app) {
  for (const Command& c : commands()) c.add(*app.add_subcommand(c.name, c.summary));
}

std::string unknownCommandMessage(int argc, char** argv) {
  int i = 1;  // past the program's own options (--max-memory VALUE)
  while (i < argc && argv[i][0] == '-') i += std::string(argv[i]) == "--max-memory" ? 2 : 1;
  if (i >= argc) return "";
  std::vector<std::string> names;
  for (const Command& c : commands()) names.push_back(c.name);
  const std::string word = argv[i], near = closestName(word, names, 3);
  if (std::find(names.begin(), names.end(), word) != names.end()) return "";
  return "unknown command '" + word.substr(0, 60) + "'" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
         " (inim --help lists the commands)";
}

}  // namespace inim::cli
