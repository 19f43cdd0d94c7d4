// `rockbench report`: scaffold, replaced by the report work in progress.
#include "cli/commands.h"

namespace rockbench::cli {

void RegisterReport(CLI::App& app) {
  app.add_subcommand("report", "(in progress)");
}

}  // namespace rockbench::cli
