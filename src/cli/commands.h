#pragma once
// Each subcommand lives in its own cmd_*.cpp and registers itself on the app.
// The callback runs the command; InputError thrown from it becomes exit status 2.
#include <CLI/CLI.hpp>
#include <string>

#include "core/geometry.h"

namespace inim::cli {

void addRenderCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addDisplayCommand(CLI::App& app);  // inim display info
void addRaysCommand(CLI::App& app);     // inim rays
void addEiaCommand(CLI::App& app);      // inim eia
void addTriadsCommand(CLI::App& app);   // inim triads export|form
void addCompareCommand(CLI::App& app);  // inim compare A B
void addLensCommand(CLI::App& app);     // inim lens info FILE
void addViewCommand(CLI::App& app);     // inim view
void addReferenceCommand(CLI::App& app);  // inim reference
void addFig11Command(CLI::App& app);    // inim fig11
void addStudyCommand(CLI::App& app);    // inim study NAME
void addQueryCommand(CLI::App& app);    // inim query --field F --rays R --out C
void addTrainCommand(CLI::App& app);    // inim train --data DIR --out MODEL
void addEvalCommand(CLI::App& app);     // inim eval --model MODEL --data DIR
void addCaptureCommand(CLI::App& app);  // inim capture --scene FILE --out DIR

// Options every command that computes shares.
struct RunOptions {
  uint64_t seed = 1;
  int threads = 0;  // 0 = all cores
};
void addRunOptions(CLI::App* cmd, RunOptions& opts);

// "x,y,z" -> vector; InputError naming the option otherwise.
Vec3 parseVec3Option(const std::string& text, const std::string& option);
// scenes/paper-fig7.json under the data folder.
std::string defaultScenePath();

}  // namespace inim::cli
