// rockbench: cross-validation harness for rocking rigid blocks.
#include <cstdio>
#include <exception>

#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"rockbench: the two-block rocking model (Roussis 1999) beside physics engines"};
  app.require_subcommand(1);
  rockbench::cli::RegisterRun(app);
  rockbench::cli::RegisterCompare(app);
  rockbench::cli::RegisterSweep(app);
  rockbench::cli::RegisterRender(app);
  rockbench::cli::RegisterReport(app);
  rockbench::cli::RegisterStress(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    // A subcommand's own failure: it printed its message; keep its exit code.
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help exits 0; every bad option or value is bad input.
    return app.exit(e) == 0 ? 0 : rockbench::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rockbench: error: %s\n", e.what());
    return rockbench::cli::kExitBadInput;
  }
  return 0;
}
