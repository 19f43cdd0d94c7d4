// Placeholder until the compare subcommand lands: it says so and exits non-zero.
#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"

namespace rockbench::cli {

void RegisterCompare(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "(not built yet)");
  cmd->allow_extras();
  cmd->callback([] {
    std::fprintf(stderr, "rockbench compare: not available in this build yet\n");
    std::exit(kExitBadInput);
  });
}

}  // namespace rockbench::cli
