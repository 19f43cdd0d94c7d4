// Placeholder until the sweep subcommand lands: it says so and exits non-zero.
#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"

namespace rockbench::cli {

void RegisterSweep(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep", "(not built yet)");
  cmd->allow_extras();
  cmd->callback([] {
    std::fprintf(stderr, "rockbench sweep: not available in this build yet\n");
    std::exit(kExitBadInput);
  });
}

}  // namespace rockbench::cli
