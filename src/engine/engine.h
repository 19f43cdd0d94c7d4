#pragma once
/// The engine interface: what the reference (src/run/reference_engine.h) and every physics
/// engine adapter (engines/<name>/) implement, and all the harness knows of an engine. An engine
/// declares its settings (the scene's [<name>] table), the settings grid it offers to the
/// work-precision sweep, and simulates a scene. The list of engines is engines/CMakeLists.txt (one
/// line each); an engine whose library is missing at build time is left out and named by `rockbench
/// engines`.
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "scene/engine_settings.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench {

/// The integrator settings of a point of an engine that integrates with an adaptive or a fixed
/// step of its own (the reference: its scene's [model] table), shown in sweep.csv's integrator,
/// rtol, atol and rk4_step_s columns.
struct IntegratorSetting {
  Integrator integrator = Integrator::kDopri5;
  double rtol = 0.0, atol = 0.0;  ///< the adaptive pairs' tolerances (0 for rk4)
  double step_s = 0.0;            ///< rk4's fixed step, s (0 for an adaptive pair)
};

/// One point of an engine's work-precision grid: the settings it changes from the scene's.
struct SweepSetting {
  /// The curve this point belongs to: "Bullet double (50 iterations)" (the settings that stay
  /// fixed along it). No commas: it is a field of sweep.csv.
  std::string family;
  /// The point's label on the curve: its time step ("1e-3", "1/60") or accuracy knob.
  std::string label;
  double time_step_s = 0.0;  ///< the step of this point (the x of the order-of-convergence fit)
  /// key -> value in the engine's table, applied as `--set <engine>.<key>=<value>` would.
  std::vector<std::pair<std::string, SettingValue>> settings;
  /// The point's integrator settings, for an engine whose points are its integrator's (the
  /// reference's); absent for a point of an engine's table (`settings`).
  std::optional<IntegratorSetting> integrator;
  /// Stress cases: the case's name under "<engine>_dt/" ("double/dt=1e-3/it=200"), and whether
  /// it is in the CI subset (stress --quick).
  std::string id;
  bool quick = false;
};

/// A time step as a point label: "1e-3", "5e-5", "1/60" (a whole number of steps per second
/// that is not a power of ten), else "%.3g".
std::string TimeStepLabel(double dt_s);

/// Two settings families of an engine, ours and the engine's own defaults, over time steps: the
/// shape of most engines' sweep and stress grids.
struct TwoFamilyGrid {
  std::string ours_family;      ///< "DART (Dantzig + PGS)": our defaults
  std::string defaults_family;  ///< "DART defaults (FCL friction 1)": the engine's own
  /// What the engine's-defaults family sets besides the step (key -> value in the table).
  std::vector<std::pair<std::string, SettingValue>> defaults_settings;
  /// The stress cases' name prefixes: "<id>/dt=<label>".
  std::string ours_id = "ours", defaults_id = "defaults";

  /// One point: the family at step dt (its label TimeStepLabel(dt)).
  SweepSetting Point(bool engine_defaults, double dt_s) const;
  /// Ours over steps_s, then the engine's defaults over steps_s (SweepGrid).
  std::vector<SweepSetting> Sweep(const std::vector<double>& steps_s) const;
  /// The same as stress cases, each in the CI subset when quick(dt) (StressGrid).
  std::vector<SweepSetting> Stress(const std::vector<double>& steps_s,
                                   const std::function<bool(double dt_s)>& quick) const;
  /// Sweep over the usual steps: quick {1e-3, 1e-4}; else coarsest_s, then 1e-3 to 1e-5 s.
  std::vector<SweepSetting> StandardSweep(bool quick, double coarsest_s) const;
  /// Stress over 1/60, 1e-3, 1e-4 and 1e-5 s, the CI subset the coarsest step of each family.
  std::vector<SweepSetting> StandardStress() const;
};

/// Options of one run.
struct SimulateOptions {
  /// The reference: check its convergence against a witness at a tighter tolerance (and use the
  /// witness when they differ). Engines have no witness and ignore it.
  bool check_convergence = true;
  /// After this time (s) a run at rest stops with status "at_rest" (harness SettledAfter_s);
  /// infinity: never. Ensemble members only: their histories are not compared.
  double stop_at_rest_after_s = std::numeric_limits<double>::infinity();
};

/// What an engine's run may carry beyond the common result, for the parts of the harness that
/// know that engine (the reference: both of its solutions and their convergence check).
struct EngineResultExtension {
  virtual ~EngineResultExtension() = default;
};

/// What one run returns.
struct EngineResult {
  History history;            ///< samples at the output interval (step times), events
  RunOutcome outcome;         ///< typed: status, peaks, impacts, violations
  nlohmann::json summary;     ///< the engine's part of summary.json (outcome, settings, monitor)
  double wall_s = 0.0;        ///< wall-clock time of the simulation alone, s
  std::string settings_line;  ///< the settings that matter, one line ("double, dt 1e-4 s")
  /// The engine's richer result, when it has one (null for the physics engines).
  std::shared_ptr<const EngineResultExtension> extension;
};

class Engine {
 public:
  virtual ~Engine() = default;
  /// The engine's name and the name of its table: "bullet".
  virtual std::string name() const = 0;
  /// Library and version as built: "Bullet 3.24 (bullet-float64, double precision)".
  virtual std::string version() const = 0;
  /// The keys of its table [<name>] with our defaults (the engine's own beside them).
  virtual const EngineSettingsSchema& settings_schema() const = 0;
  /// The settings grid of the work-precision sweep (quick: the CI's few points).
  virtual std::vector<SweepSetting> SweepGrid(bool quick) const = 0;
  /// The settings the stress catalogue runs on the thesis's free rocking: the extremes (the
  /// coarsest steps, the fewest iterations) where the engine's artefacts show.
  virtual std::vector<SweepSetting> StressGrid() const = 0;
  /// The scene of one point of its grids: `base` with the point's settings (default: each of
  /// `setting.settings` set in the engine's table, as `--set <engine>.<key>=<value>` would).
  virtual Scene SceneForSetting(const Scene& base, const SweepSetting& setting) const;
  /// Where its part of a run's summary.json goes (a JSON pointer): "/engines/<name>" by
  /// default; "" for the top level (the reference's, the file's own subject).
  virtual std::string SummaryPointer() const;
  /// The body kinds it builds (BodyKind::shape, scene/body_kind.h): the planar rigid block
  /// unless it says otherwise. RunEngine refuses a scene of another kind (CheckBuildsBodies).
  virtual std::vector<std::string> body_shapes() const;
  /// Simulates the scene under `motion`. Physics outcomes never throw (a blow-up is a status);
  /// throws SceneError for settings the engine cannot run (naming the key).
  virtual EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                                const SimulateOptions& options) const = 0;
  /// The run in one line for the terminal: "bullet (double, dt 1e-4 s): completed, peak
  /// |theta1| 0.15 rad at 0.000 s, 54 impacts, flags: none, 2.31e+03 ms".
  virtual std::string SummaryLine(const EngineResult& result) const;
};

/// Throws SceneError (naming the scene's file, block1.shape, the engine and the kinds it builds)
/// when `engine` does not build the bodies of `scene`.
void CheckBuildsBodies(const Engine& engine, const Scene& scene);

}  // namespace rockbench
