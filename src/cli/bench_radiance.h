#pragma once
// The radiance-field benchmarks of `inim bench` (registered only when their inputs are given):
//   radiance/eia-query   the default display's EIA (6,215,625 query rays) from a trained model
//                        (--field-model, placed by --field-scale/--field-rotate-deg/
//                        --field-translate-mm); target <= 30 s on 2 cores
//   radiance/train-lego  train on the Lego scene (--lego DIR) at 200 x 200, every 8th view held
//                        out; reports the held-out PSNR; target >= 28 dB within 10 minutes
#include <CLI/CLI.hpp>
#include <string>

namespace inim::cli {

struct RadianceBenchOptions {
  std::string model, scale, rotate, translate, lego;
  int legoIterations = 3000;
};
void addRadianceBenchOptions(CLI::App* cmd, RadianceBenchOptions& o);
void registerRadianceBenchmarks(const RadianceBenchOptions& o);
// The results table (after RunSpecifiedBenchmarks).
void printRadianceBenchResults();

}  // namespace inim::cli
