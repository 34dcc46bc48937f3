#pragma once
// Helpers shared by the command-line tests: files, data paths, and the bad-input check
// (status 2, a message naming what is wrong, no output or temporary left behind).
#include "fixtures.h"
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "cli/run_cli.h"

inline void writeText(const std::string& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

inline std::string data(const std::string& rel) { return std::string(INIM_SOURCE_DATA_DIR) + "/" + rel; }

// A small display: K x R EIs of n px (0.1 mm pixels), panel with a 3 px border.
inline std::string smallDisplayJson(int K, int R, int n, double gap = 3.0, double pitch = 0.9, int panelW = 0,
                                    int panelH = 0) {
  return fixtures::smallDisplayJson({K, R, n, gap, pitch, panelW, panelH});
}

// A 2-node .cube calibration LUT that multiplies every drive value by `k` (affine, so
// tetrahedral interpolation is exact at any input), written to `file`.
inline std::string writeScalingCube(const std::string& file, double k) {
  std::string text = "TITLE \"x" + std::to_string(k) + "\"\nLUT_3D_SIZE 2\n";
  for (int i = 0; i < 8; ++i)
    text += std::to_string(k * (i & 1)) + " " + std::to_string(k * (i >> 1 & 1)) + " " +
            std::to_string(k * (i >> 2 & 1)) + "\n";
  writeText(file, text);
  return file;
}

// Runs `args` with `runner` (runInim, or a test's own binary) and expects a bad-input failure.
template <class Runner>
void expectBadInputWith(Runner runner, const std::string& args, std::initializer_list<std::string> needles,
                        std::initializer_list<std::string> outputs) {
  namespace fs = std::filesystem;
  CliResult r = runner(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("inim: error:"), std::string::npos) << r.output;
  for (const auto& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << "message lacks '" << n << "':\n" << r.output;
  for (const auto& o : outputs) {
    EXPECT_FALSE(fs::exists(o)) << o << " was left behind by: " << args;
    if (!fs::exists(fs::path(o).parent_path())) continue;
    for (const auto& e : fs::directory_iterator(fs::path(o).parent_path()))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "temporary left: " << e.path();
  }
}
