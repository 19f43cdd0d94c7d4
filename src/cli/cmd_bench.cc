// Placeholder until the bench subcommand lands: it says so and exits non-zero.
#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"

namespace rockbench::cli {

void RegisterBench(CLI::App& app) {
  auto* cmd = app.add_subcommand("bench", "(not built yet)");
  cmd->allow_extras();
  cmd->callback([] {
    std::fprintf(stderr, "rockbench bench: not available in this build yet\n");
    std::exit(kExitBadInput);
  });
}

}  // namespace rockbench::cli
