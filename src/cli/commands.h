#pragma once
// The commands, in one table: each lives in its own cmd_*.cpp, where its add function takes
// the subcommand the table made (name and summary from here) and adds its options: it parses
// them into the library's settings, calls the library and prints. InputError thrown from it
// becomes exit status 2 (main.cpp), its setting named by its flag (cli/options.h). Adding a
// command is a cmd_*.cpp and a line in commands.cpp.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace inim::cli {

struct Command {
  const char* name;
  const char* summary;  // one line, as --help shows it
  void (*add)(CLI::App& cmd);
};

// Every command, in the order --help lists them.
const std::vector<Command>& commands();
// Adds every command of the table to `app`.
void addCommands(CLI::App& app);
// For a command line whose command is not in the table: "unknown command 'X'" and the nearest
// name; "" otherwise.
std::string unknownCommandMessage(int argc, char** argv);

void addRenderCommand(CLI::App& cmd);
void addDisplayCommand(CLI::App& cmd);
void addRaysCommand(CLI::App& cmd);
void addEiaCommand(CLI::App& cmd);
void addPlaceCommand(CLI::App& cmd);
void addTriadsCommand(CLI::App& cmd);
void addViewCommand(CLI::App& cmd);
void addReferenceCommand(CLI::App& cmd);
void addFig11Command(CLI::App& cmd);
void addCalibrateCommand(CLI::App& cmd);
void addStudyCommand(CLI::App& cmd);
void addQueryCommand(CLI::App& cmd);
void addCaptureCommand(CLI::App& cmd);
void addTrainCommand(CLI::App& cmd);
void addEvalCommand(CLI::App& cmd);
void addCompareCommand(CLI::App& cmd);
void addLensCommand(CLI::App& cmd);
void addBenchCommand(CLI::App& cmd);
void addSweepCommand(CLI::App& cmd);

}  // namespace inim::cli
