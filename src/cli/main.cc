// rockbench: cross-validation harness for rocking rigid blocks.
#include <cstdio>
#include <exception>

#include "cli/commands.h"
#include "run/engine_registry.h"
#include "study/study_mpi.h"
#include "util/wall_limit.h"

namespace rockbench::cli {

// Whether `mpirun ... rockbench ensemble` works in this build.
std::string MpiLine() {
  return MpiBuilt() ? "mpi: built (mpirun -n N rockbench ensemble ...)\n"
                    : "mpi: left out of this build (" + MpiMissingReason() + ")\n";
}

void RegisterEngines(CLI::App& app) {
  auto* cmd = app.add_subcommand("engines", "List the engines of this build and those left out");
  cmd->callback([] {
    std::printf("reference: the analytical model (always built)\n%s%s", EngineListText().c_str(),
                MpiLine().c_str());
  });
}

}  // namespace rockbench::cli

namespace {

// The command line's work; main() adds what every command shares (signals, cleanup).
int Main(int argc, char** argv) {
  CLI::App app{"rockbench: the rocking-block stack model (Roussis 1999) beside physics engines"};
  app.require_subcommand(0, 1);
  bool version = false;
  app.add_flag("--version", version, "Print the version and the engines of this build");
  rockbench::cli::RegisterRun(app);
  rockbench::cli::RegisterCompare(app);
  rockbench::cli::RegisterSweep(app);
  rockbench::cli::RegisterRender(app);
  rockbench::cli::RegisterReport(app);
  rockbench::cli::RegisterStress(app);
  rockbench::cli::RegisterEnsemble(app);
  rockbench::cli::RegisterEngines(app);
  try {
    app.parse(argc, argv);
    if (version) {
      std::printf("rockbench %s\nreference: the analytical model\n%s%s", ROCKBENCH_VERSION,
                  rockbench::EngineListText().c_str(), rockbench::cli::MpiLine().c_str());
      return 0;
    }
    if (app.get_subcommands().empty()) {
      std::fprintf(stderr, "%s", app.help().c_str());
      return rockbench::cli::kExitBadInput;
    }
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

}  // namespace

int main(int argc, char** argv) {
  // First: SIGTERM, SIGINT and SIGHUP end every process rockbench started
  // (and theirs: an engine's helper that left its group with setsid is re-parented to
  // rockbench, the subreaper) and remove its temporary files (util/wall_limit.h).
  rockbench::HandleTerminationSignals();
  rockbench::BecomeSubreaper();
  const int code = Main(argc, argv);
  // Whatever an engine left running ends with rockbench.
  rockbench::CleanUpAtExit();
  return code;
}
