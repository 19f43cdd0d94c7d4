#pragma once
/// The reference (the analytical two-block model, reference/) behind the engine interface
/// (scene/engine.h), so that the harness runs it as it runs any engine. Its run solves the scene
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
/// settings are the scene's [model] table), no sweep or stress grid (sweep and stress vary the
/// [model] settings themselves).
class ReferenceEngine final : public Engine {
 public:
  std::string name() const override { return std::string(kReferenceEngine); }
  std::string version() const override;
  const EngineSettingsSchema& settings_schema() const override;
  std::vector<SweepSetting> SweepGrid(bool) const override { return {}; }
  std::vector<SweepSetting> StressGrid() const override { return {}; }
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
