// Placeholder until the render subcommand lands: it says so and exits non-zero.
#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"

namespace rockbench::cli {

void RegisterRender(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "(not built yet)");
  cmd->allow_extras();
  cmd->callback([] {
    std::fprintf(stderr, "rockbench render: not available in this build yet\n");
    std::exit(kExitBadInput);
  });
}

}  // namespace rockbench::cli
