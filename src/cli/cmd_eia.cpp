#include "cli/commands.h"
namespace inim::cli {
void addEiaCommand(CLI::App& app) { app.add_subcommand("eia", "(being written)"); }
}
