#pragma once
/// The stress catalogue: named stiff and extreme cases (slenderness, mass ratio, size, uplift
/// thresholds, strong and fast excitation, release at the overturning angle, impact cascades,
/// vertical acceleration past -g, every engine's extreme settings from its StressGrid), each
/// run with the reference model and every built engine, each giving one row of stress.csv:
/// finished or not, status, NaN/Inf seen, largest energy gain across an impact, event count,
/// smallest time between impacts, wall time, and for an engine its settings, violations and
/// agreement with the reference. Every (case, engine) runs in a child process with a wall-clock
/// limit, so a crash or a hang becomes a row, never the end of the command. See docs/stress.md.
/// Sources: stress_catalogue.cc (the cases), stress_run.cc (one run, and the pool of children),
/// stress_rows.cc (a row as JSON and as CSV).
#include <algorithm>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "scene/scene.h"

namespace rockbench {

/// Hidden cases that prove the isolation works: the child crashes or hangs on purpose.
enum class StressSelfTest { kNone, kCrash, kHang };

/// One named case of the catalogue.
struct StressCase {
  std::string name;         ///< hierarchical, e.g. "uplift/stack/below_1pct"
  std::string description;  ///< what it checks, one line
  Scene scene;              ///< built in code (no file)
  /// The engines it runs on: "reference" and engine names; empty: the reference and every
  /// engine of this build.
  std::vector<std::string> engines;
  /// An engine settings case: the engine's settings it sets (Engine::StressGrid).
  std::optional<SweepSetting> setting;
  double wall_limit_s = 60.0;  ///< the child is killed after this wall time, s
  bool quick = false;          ///< part of the CI subset (--quick)
  /// Run only when a --case pattern names it (pattern starting with "selftest").
  bool hidden = false;
  StressSelfTest self_test = StressSelfTest::kNone;
};

/// Which face opens first under a constant horizontal base acceleration from rest.
enum class UpliftKind {
  kStack,  ///< block 1 on the ground (the stack tips about block 1's corner)
  kTop,    ///< block 2 on block 1 (block 2 tips on block 1)
};

/// The smallest constant horizontal base acceleration (m/s^2, magnitude) at which the face
/// contact of `kind` opens from rest: bisection on the sign of the smaller corner force of that
/// face given by the reference's own contact rule (reference::EvaluateContacts in mode rest,
/// the rule that reproduces the thesis's initiation criteria 4.1-4.4), to a relative width of
/// 1e-13. For one block, kStack is Housner's g b / h. kTop needs two blocks (throws SceneError).
double UpliftThreshold_mps2(const Scene& scene, UpliftKind kind);

/// The thesis's geometry (section 6.3): B1 = H1 = 1.25 m, B2 = 1 m, H2 = 2.5 m, 2500 kg/m^3,
/// at rest, no base motion, 5 s, output every 0.01 s.
Scene ThesisStackScene();

/// The whole catalogue in its fixed order (hidden self-test cases last). Deterministic.
std::vector<StressCase> StressCatalogue();

/// Cases selected by `patterns` (each a glob, fnmatch rules, or a name prefix), in catalogue
/// order; no patterns: every non-hidden case. `quick` keeps only the CI subset among them.
/// Hidden cases are selected only by a pattern that starts with "selftest". Throws SceneError
/// naming a pattern that selects nothing.
std::vector<StressCase> SelectStressCases(const std::vector<StressCase>& catalogue,
                                          const std::vector<std::string>& patterns, bool quick);

/// One row of stress.csv.
struct StressRow {
  std::string case_name;
  std::string engine;
  /// The run reached its end time or a physics ending (overturned, at rest, assumption
  /// violated); false for blow_up, non_finite, crash, wall_limit and error.
  bool finished = false;
  /// completed | overturned | at_rest | assumption_violated (reference) | blow_up (engines) |
  /// non_finite (either: the run stopped at its last finite state) | "crash (signal N)" |
  /// wall_limit | "error (exit N)".
  std::string status;
  std::string detail;  ///< why (status detail, error message), no commas
  /// A non-finite value in the history, events or summary, or status non_finite (a run that
  /// stopped where a value stopped being finite).
  bool nan = false;
  /// Largest (E_after - E_before) / KE_before over the impacts (see docs/stress.md); 0 when
  /// no impact qualifies. Negative: every impact dissipated.
  double max_energy_gain_rel = 0.0;
  int energy_impacts = 0;  ///< impacts that entered max_energy_gain_rel
  int events = 0;          ///< all events (impacts, transitions, initiations, rest, overturn...)
  int impacts = 0;         ///< ground and interface impacts
  /// Smallest time between consecutive impacts, s; < 0 when fewer than two impacts.
  double min_event_gap_s = -1.0;
  double wall_s = 0.0;  ///< the engine's simulation wall time (process time if it failed), s
  /// Per body (body k at k - 1): peak |theta_k|, rad; empty when the run gave none.
  std::vector<double> peak_theta_rad;
  // Engine rows: settings.
  bool has_settings = false;
  double dt_s = 0.0;     ///< the engine's time step, s
  std::string settings;  ///< the settings the case sets besides the step ("k=v;k=v")
  /// Engine rows: violations flagged by the monitor ("sliding;uplift;..." or "none").
  std::string violations;
  // Engine rows: agreement with the reference (CompareWithReference).
  bool has_agreement = false;
  /// Per body: the largest error of its angle, rad, and its peak's relative error.
  std::vector<double> max_abs_error_rad, peak_rel_error;
  int impacts_matched = 0, reference_impacts = 0;
  /// Bodies of the case's stack as the columns count them: 2 for one or two bodies (their
  /// columns are the same), N for N >= 3.
  int column_blocks() const { return std::max(2, static_cast<int>(peak_theta_rad.size())); }
};

/// Runs one engine on one case in this process (what the child does). Never throws for
/// physics outcomes; a self-test case crashes or hangs here on purpose.
StressRow RunStressCaseHere(const StressCase& c, const std::string& engine);

/// A row as one line of JSON (the child's stdout) and back. FromJson throws on bad input.
nlohmann::json StressRowToJson(const StressRow& row);
StressRow StressRowFromJson(const nlohmann::json& j);

/// How RunStress runs the children.
struct StressRunOptions {
  /// The program re-executed as `PROGRAM stress --run-case NAME --engine E` (the rockbench
  /// executable); empty: SelfExecutable().
  std::filesystem::path executable;
  int jobs = 0;  ///< children at once; 0: std::thread::hardware_concurrency()
};

/// Progress: (rows done, rows total, the row just finished). One call at a time.
using StressProgress = std::function<void(int, int, const StressRow&)>;

/// Runs every (case, engine) of `cases` in a child process under its wall-clock limit, up to
/// options.jobs at once. Rows in catalogue order (case, then its engines' order). A child that
/// crashes, hangs or prints no row becomes a row with that status. Throws SceneError for
/// jobs < 0.
std::vector<StressRow> RunStress(const std::vector<StressCase>& cases,
                                 const StressRunOptions& options,
                                 const StressProgress& progress = {});

/// stress.csv: header and one line per row. Only wall_s depends on the machine and the run.
/// With a row of N >= 3 blocks, the columns of blocks 3..N of the largest such stack follow
/// those of block 2 (peak_theta3_rad, ... after peak_theta2_rad; theta3_max_abs_error_rad,
/// theta3_peak_rel_error, ... after theta2_peak_rel_error), empty in a row of fewer blocks;
/// without one the columns are those of one and two blocks.
std::string StressCsv(const std::vector<StressRow>& rows);

}  // namespace rockbench
