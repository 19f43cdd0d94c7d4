#pragma once
/// The reference (the analytical two-block model, reference/) behind the engine interface
/// (engine/engine.h), so that the harness runs it as it runs any engine. Its run solves the scene
/// twice, at the scene's tolerance and at a tighter one (the witness, run/reference_witness.h),
/// and reports the witness when the two differ by more than the comparison tolerance. The richer
/// result (both solutions, the check, the events and modes) travels as the run's extension.
#include <memory>

#include "engine/engine.h"
#include "run/engine_registry.h"
#include "run/reference_witness.h"

namespace rockbench {

/// The reference's extension of its EngineResult: both solutions and their convergence check.
struct ReferenceExtension : EngineResultExtension {
  CheckedReference checked;
};

/// The reference model as an engine: name "reference", no settings table of its own (its
/// settings are the scene's [model] table), a sweep grid of its integrators' tolerances and
/// steps (points that set the scene's [model] integrator), no stress grid (the stress catalogue
/// runs it on every case).
class ReferenceEngine final : public Engine {
 public:
  std::string name() const override { return std::string(kReferenceEngine); }
  std::string version() const override;
  const EngineSettingsSchema& settings_schema() const override;
  /// Full: dopri5 at rtol 1e-4 ... 1e-12, dop853 at 1e-6 ... 1e-12 (atol = rtol / 100), RK4 at
  /// steps 1e-2, 1e-3, 1e-4 s; quick: dopri5 at 1e-4, 1e-6, 1e-8 and RK4 at 1e-3 s.
  std::vector<SweepSetting> SweepGrid(bool quick) const override;
  std::vector<SweepSetting> StressGrid() const override { return {}; }
  /// `base` with the point's integrator, tolerances or step in its [model] table.
  Scene SceneForSetting(const Scene& base, const SweepSetting& setting) const override;
  /// The top level: summary.json is the reference's run, the engines' beside it.
  std::string SummaryPointer() const override { return ""; }
  /// The planar block (the thesis's model) and the cylinder (reference/cylinder_run.h).
  std::vector<std::string> body_shapes() const override;
  /// A point of its grid: an adaptive pair at `rtol` (atol = rtol / 100), family "reference
  /// dopri5" or "reference dop853", labelled by the rtol.
  static SweepSetting TolerancePoint(Integrator integrator, double rtol);
  /// A point of its grid: fixed-step RK4 at `step_s` (s), family "reference RK4".
  static SweepSetting Rk4Point(double step_s);
  /// Solves the scene (and its witness unless options.check_convergence is false). Never throws
  /// for physics: a failed solution is status non_finite with its detail.
  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override;
  /// "reference: at_rest, peak |theta1| ... rad at ... s, peak |theta2| ..., N impacts, T ms",
  /// with the witness's warning when the reference did not converge.
  std::string SummaryLine(const EngineResult& result) const override;
};

/// The one reference engine of the program.
const ReferenceEngine& TheReference();

/// The reference's own result, from the extension of a run of the reference engine
/// (EngineResult::extension, EngineRun::extension); null for any other engine's.
const CheckedReference* ReferenceResultOf(const EngineResultExtension* extension);

}  // namespace rockbench
