#include "cli/commands.h"
namespace inim::cli {
void addDisplayCommand(CLI::App& app) { app.add_subcommand("display", "(being written)"); }
}
