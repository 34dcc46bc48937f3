#include "cli/commands.h"
namespace inim::cli {
void addRaysCommand(CLI::App& app) { app.add_subcommand("rays", "(being written)"); }
}
