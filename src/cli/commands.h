#pragma once
// Each subcommand lives in its own cmd_*.cpp and registers itself on the app.
// The callback runs the command; InputError thrown from it becomes exit status 2.
#include <CLI/CLI.hpp>

namespace inim::cli {

void addRenderCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addDisplayCommand(CLI::App& app);  // inim display info
void addRaysCommand(CLI::App& app);     // inim rays
void addEiaCommand(CLI::App& app);      // inim eia

// Options every command that computes shares.
struct RunOptions {
  uint64_t seed = 1;
  int threads = 0;  // 0 = all cores
};
void addRunOptions(CLI::App* cmd, RunOptions& opts);

}  // namespace inim::cli
