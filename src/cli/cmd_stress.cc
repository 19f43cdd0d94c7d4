// `rockbench stress`: scaffold, replaced by the stress work in progress.
#include "cli/commands.h"

namespace rockbench::cli {

void RegisterStress(CLI::App& app) {
  app.add_subcommand("stress", "(in progress)");
}

}  // namespace rockbench::cli
