#pragma once
/// Accuracy/cost sweep: runs the engines over a grid of settings (each engine's own grid,
/// Engine::SweepGrid; reference: dopri5 tolerances and fixed-step RK4 steps) and compares
/// each run with a tight-tolerance reference (dopri5, rtol 1e-12). Runs in parallel on a
/// std::thread pool; rows come out in the grid's fixed order, so every column but the wall
/// times is independent of the number of threads.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/agreement.h"
#include "engine/engine.h"
#include "motion/ground_motion.h"
#include "scene/scene.h"

namespace rockbench {

/// One grid point: an engine and one point of its grid (Engine::SweepGrid).
struct SweepPoint {
  std::string engine;  ///< a registered engine's name, or "reference"
  /// The point: family, label, time step and the engine's table settings, or the integrator
  /// settings of an engine that has them (the reference's tolerances and steps).
  SweepSetting setting;
};

/// The grid, in row order: every engine of `engines` with its own grid (Engine::SweepGrid),
/// then the reference's (ReferenceEngine::SweepGrid: its tolerances and RK4 steps), each engine
/// once (the reference, always swept, last).
std::vector<SweepPoint> SweepGrid(bool quick, const std::vector<std::string>& engines);
/// The reference's fixed-step RK4 at `step_s` (s): a point of the grid, or a chosen one.
SweepPoint ReferenceRk4Point(double step_s);
/// The reference's adaptive pair `integrator` at `rtol` (atol = rtol / 100).
SweepPoint ReferenceTolerancePoint(Integrator integrator, double rtol);

/// The scene of a grid point: `base` with the point's settings (Engine::SceneForSetting).
Scene SceneForPoint(const Scene& base, const SweepPoint& point);

struct SweepOptions {
  bool quick = false;
  int repeat = 1;   ///< repetitions per point; the row's wall time is their minimum
  int threads = 0;  ///< worker threads; 0: std::thread::hardware_concurrency()
  /// Engines swept (every built engine when empty); the reference is always swept.
  std::vector<std::string> engines;
  /// When non-empty, these points are run instead of SweepGrid(quick, ...) (tests, studies).
  std::vector<SweepPoint> points;
};

/// Tolerances of the tight reference every row is compared with (dopri5).
inline constexpr double kSweepTightRtol = 1e-12;
inline constexpr double kSweepTightAtol = 1e-14;

/// The tight reference every row is compared with (dopri5, kSweepTightRtol/Atol).
struct SweepBaseline {
  double wall_s = 0.0;                       ///< its wall time, s
  RunStatus status = RunStatus::kCompleted;  ///< its summary status (completed, overturned, ...)
  /// Per body (body k at k - 1): peak |theta_k| over the run, rad, and its time, s (0: the
  /// release angle is the peak).
  std::vector<double> peak_theta_rad, peak_theta_t_s;
  int overturn_block = 0;  ///< 1..N when a block overturned, else 0
  double overturn_t_s = 0.0;
  int blocks() const { return static_cast<int>(peak_theta_rad.size()); }
};

/// One row of sweep.csv.
struct SweepRow {
  SweepPoint point;
  double wall_s = 0.0;  ///< minimum over the repetitions, s
  EngineAgreement agreement;
  std::string error;  ///< non-empty when the run failed (its message)
};

/// Progress callback: (runs done, runs total, the point just finished). Called from worker
/// threads, one call at a time.
using SweepProgress = std::function<void(int, int, const SweepPoint&)>;

/// Runs the sweep on a scene. The tight reference runs first (described in *baseline when
/// given). Throws SceneError for bad options.
std::vector<SweepRow> RunSweep(const Scene& scene, const GroundMotion& motion,
                               const SweepOptions& options, const SweepProgress& progress = {},
                               SweepBaseline* baseline = nullptr);

/// sweep.csv text: header and one row per grid point, in grid order. A stack of `blocks` >= 3
/// blocks has the five theta columns of every block k = 3..N after theta2's (thetak_max_abs_
/// error_rad, thetak_rms_error_rad, thetak_horizon_s, thetak_peak_rel_error,
/// thetak_peak_time_error_s); one or two blocks, the columns of theta1 and theta2.
std::string SweepCsv(const std::vector<SweepRow>& rows, int blocks = 2);

/// The machine, without dates or names: "CPU model, N hardware threads, Linux x86_64".
std::string MachineDescription();

/// sweep.json, written beside sweep.csv: what a report needs that the rows do not say. Keys:
/// scene.path, scene.title, scene.overrides (as given), simulated_duration_s (the scene's
/// run.duration, the real-time mark), two_blocks, options.quick / repeat / threads,
/// tight_reference.rtol / atol / wall_s / status / peak_theta1_rad / peak_theta1_t_s /
/// peak_theta2_rad / peak_theta2_t_s / overturn_block (null or 1..N) / overturn_t_s, runs,
/// failed, machine; N >= 3 blocks also blocks (N) and tight_reference.peak_thetak_rad /
/// peak_thetak_t_s of k = 3..N. No dates; only the wall times change from run to run.
nlohmann::json SweepJson(const Scene& scene, const std::vector<std::string>& overrides,
                         const SweepOptions& options, const SweepBaseline& baseline,
                         const std::vector<SweepRow>& rows);

}  // namespace rockbench
