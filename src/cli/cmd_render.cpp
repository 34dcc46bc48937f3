#include "cli/commands.h"
namespace inim::cli {
void addRenderCommand(CLI::App& app) { app.add_subcommand("render", "Render a scene (in progress)"); }
}
