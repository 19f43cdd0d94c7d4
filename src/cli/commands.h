#pragma once
/// CLI subcommands. Each file registers one subcommand on the CLI11 app; main.cc calls them all.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

namespace rockbench::cli {

/// `rockbench run SCENE --out DIR [--engine NAME] [--set key=value ...]` (cmd_run.cc)
void RegisterRun(CLI::App& app);
/// `rockbench compare SCENE --out DIR [--engines all|NAME,...]` (cmd_compare.cc)
void RegisterCompare(CLI::App& app);
/// `rockbench sweep SCENE --out DIR` (cmd_sweep.cc)
void RegisterSweep(CLI::App& app);
/// `rockbench render SCENE_OR_RUN_DIR --out DIR ...` (cmd_render.cc)
void RegisterRender(CLI::App& app);
/// `rockbench report RUN_DIR... --out DIR` (cmd_report.cc)
void RegisterReport(CLI::App& app);
/// `rockbench stress --out DIR [--quick]` (cmd_stress.cc)
void RegisterStress(CLI::App& app);

/// `rockbench ensemble STUDY --out DIR [--jobs N] [--resume]` (cmd_ensemble.cc)
void RegisterEnsemble(CLI::App& app);

/// `rockbench engines`: the engines of this build, and those left out (main.cc)
void RegisterEngines(CLI::App& app);

/// Exit code for bad input (scene, record, option): 2. Physics outcomes exit 0.
inline constexpr int kExitBadInput = 2;
/// Exit code of `run` and `compare` when a run ended non_finite (its state, energy, an event time
/// or a contact force stopped being finite; run/engine_run.h): 4. The outputs are written, each
/// ending at its run's last finite state, and stderr names every failed run.
inline constexpr int kExitRunFailed = 4;
/// Exit code of `run` and `compare` when the reference's model stopped deciding the motion (an
/// impact or a contact state with no admissible outcome or several: summary.json
/// "undetermined"): 5. The outputs are written; from that instant the history is the outcome the
/// model's rule chose, one of several (or none) that the model admits, and stderr says where and
/// why.
inline constexpr int kExitUndetermined = 5;

/// What `run` and `compare` say on stderr where the reference's model stopped deciding the
/// motion: "the model stops deciding the motion at t = T s (DETAIL)".
inline std::string StopsDecidingText(double t_s, const std::string& detail) {
  char t[32];
  std::snprintf(t, sizeof t, "%.4f", t_s);
  return std::string("the model stops deciding the motion at t = ") + t + " s (" + detail + ")";
}

}  // namespace rockbench::cli
