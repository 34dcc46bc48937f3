#include "cli/commands.h"
namespace inim::cli {
void addBenchCommand(CLI::App& app) { app.add_subcommand("bench", "Benchmarks (in progress)"); }
}
