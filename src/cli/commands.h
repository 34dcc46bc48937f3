#pragma once
// Each subcommand lives in its own cmd_*.cpp and registers itself on the app: it parses its
// options into the library's settings, calls the library and prints. InputError thrown from
// it becomes exit status 2 (main.cpp), its setting named by its flag (cli/options.h).
#include <CLI/CLI.hpp>

namespace inim::cli {

void addRenderCommand(CLI::App& app);     // inim render
void addBenchCommand(CLI::App& app);      // inim bench
void addDisplayCommand(CLI::App& app);    // inim display info
void addRaysCommand(CLI::App& app);       // inim rays
void addEiaCommand(CLI::App& app);        // inim eia
void addTriadsCommand(CLI::App& app);     // inim triads export|form
void addCompareCommand(CLI::App& app);    // inim compare A B
void addLensCommand(CLI::App& app);       // inim lens info FILE
void addViewCommand(CLI::App& app);       // inim view
void addReferenceCommand(CLI::App& app);  // inim reference
void addFig11Command(CLI::App& app);      // inim fig11
void addCalibrateCommand(CLI::App& app);  // inim calibrate
void addStudyCommand(CLI::App& app);      // inim study NAME
void addQueryCommand(CLI::App& app);      // inim query --field F --rays R --out C
void addTrainCommand(CLI::App& app);      // inim train --data DIR --out MODEL
void addEvalCommand(CLI::App& app);       // inim eval --model MODEL --data DIR
void addCaptureCommand(CLI::App& app);    // inim capture --scene FILE --out DIR
void addPlaceCommand(CLI::App& app);      // inim place [--scene F | --field M]

}  // namespace inim::cli
