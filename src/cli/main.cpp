// inim: one program, one subcommand per job. See README.md for a tour.
#include <cstdio>
#include <exception>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/output_file.h"
#include "core/size_budget.h"

int main(int argc, char** argv) {
  inim::installInterruptHandlers();  // Ctrl-C / SIGTERM: unwind (removing temporaries), exit 130 / 143
  CLI::App app{"inim: spectral simulator for integral-imaging light-field displays"};
  app.set_version_flag("--version", std::string("inim ") + INIM_VERSION);
  app.require_subcommand(1);
  // --max-memory is global: before the command or among its options (fallthrough hands options a
  // command does not know to this app).
  app.fallthrough();
  app.add_option_function<std::string>(
      "--max-memory",
      [](const std::string& text) { inim::setMemoryLimitBytes(inim::parseByteSize(text, "--max-memory")); },
      "Largest allocation a command may make from its input, e.g. 8G or 512M (default: 16G, or 3/4 of the "
      "physical memory when that is less); larger sizes are refused before any work");
  inim::cli::addCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const inim::Interrupted& e) {
    std::fprintf(stderr, "inim: interrupted by signal %d; unfinished outputs removed\n", e.signal);
    return e.exitStatus();
  } catch (const CLI::ParseError& e) {
    if (const std::string unknown = inim::cli::unknownCommandMessage(argc, argv); !unknown.empty())
      return std::fprintf(stderr, "inim: error: %s\n", unknown.c_str()), inim::kExitBadInput;
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return std::fprintf(stderr, "inim: error: %s (--help lists the options)\n", e.what()), inim::kExitBadInput;
  } catch (const inim::GradeFailed& e) {
    std::fprintf(stderr, "inim: grade failed: %s\n", e.what());
    return inim::kExitGradeFailed;
  } catch (const inim::InputError& e) {
    std::fprintf(stderr, "inim: error: %s\n", inim::withOutputNames(inim::cli::asCommandLineError(e).what()).c_str());
    return inim::kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "inim: failed: %s\n", inim::withOutputNames(e.what()).c_str());
    return 1;
  }
  // A signal after the last commit: the outputs are whole, but the stop request is still told.
  if (int sig = inim::interruptSignal()) return inim::Interrupted{sig}.exitStatus();
  return 0;
}
