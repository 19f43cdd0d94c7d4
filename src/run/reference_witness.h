#pragma once
/// The reference's own convergence: every reference run is checked against a witness, the same
/// model at a tighter tolerance. When the two differ by more than the comparison tolerance the
/// reference is not converged, the run says so, and comparisons use the witness instead.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_run.h"
#include "run/tolerance.h"
#include "scene/scene.h"

namespace rockbench {

/// The witness's settings: an adaptive run's witness is the other Dormand-Prince pair (dopri5
/// for dop853, dop853 for dopri5) at rtol / 100 and atol / 100: a different method as well as
/// a tighter tolerance, because a pair's steps are often capped by the record's samples and
/// the longest step, so that its own run at rtol / 100 can be the same run, bit for bit (dop853
/// on Rinaldi 228 at rtol 1e-12 and 1e-14: docs/performance-reference.md), a witness that
/// cannot disagree. rk4 at a quarter of the step (4th order: 256x); the thesis's event scheme
/// (first order in the step) at a tenth of the step.
ModelConfig WitnessModel(const ModelConfig& model);

/// Difference between a reference run and its witness.
struct ConvergenceCheck {
  ModelConfig witness;  ///< the witness's model settings
  /// Per block, block k at k - 1 (one entry per block of the scene; at least two, as one block
  /// always had: its second is 0):
  std::vector<double> tolerance_rad = {0, 0};     ///< AngleTolerance_rad of the nominal run
  std::vector<double> max_abs_diff_rad = {0, 0};  ///< the largest difference over the run
  /// First time any block's difference exceeds its tolerance; nullopt: never.
  std::optional<double> diverges_at_s;
  bool same_status = true;  ///< both runs end the same way (status and overturned block)
  /// How and when each run ended (the warning says it when they differ).
  RunStatus nominal_status = RunStatus::kCompleted, witness_status = RunStatus::kCompleted;
  double nominal_end_s = 0.0, witness_end_s = 0.0;
  bool converged = true;  ///< never diverges and ends the same way
  /// Which of the two ended non_finite (run/engine_run.h IsNonFinite): such a run failed, and
  /// the solution used is the failed one, so that the failure is reported, never hidden behind
  /// the other run.
  bool nominal_non_finite = false, witness_non_finite = false;
  double witness_wall_s = 0.0;
  double max_abs_diff() const {
    double m = 0.0;
    for (const double d : max_abs_diff_rad) m = std::max(m, d);
    return m;
  }
  /// Whether comparisons use the witness: the nominal run when it failed, else the witness when
  /// it failed or the nominal run is not converged.
  bool use_witness() const {
    if (nominal_non_finite) return false;
    return witness_non_finite || !converged;
  }
};

/// Compares two runs of the same scene (nominal and witness) on the union of their sample
/// times, every block's angle.
ConvergenceCheck CompareWithWitness(const Scene& scene, const reference::Result& nominal,
                                    const reference::Result& witness);

/// A reference run with its convergence check.
struct CheckedReference {
  reference::Result nominal;
  double nominal_wall_s = 0.0;
  std::optional<reference::Result> witness;  ///< absent when the check was not asked for
  std::optional<ConvergenceCheck> check;
  /// The solution comparisons use: the witness when the nominal run is not converged, and
  /// whichever of the two ended non_finite (ConvergenceCheck::use_witness).
  const reference::Result& used() const {
    return check && check->use_witness() && witness ? *witness : nominal;
  }
};

/// Runs the reference on the scene and, when `with_witness`, its witness.
CheckedReference RunCheckedReference(const Scene& scene, const GroundMotion& motion,
                                     bool with_witness = true);

/// summary.json "convergence": {"witness": {...settings}, "max_abs_diff_rad": x,
/// "max_abs_diff_rad_per_block": {"theta1": x, ..., "thetaN": x}, "tolerance_rad": {...},
/// "converged": bool,
/// "diverges_at_s": null | t, "same_status": bool, "used": "nominal" | "witness" (use_witness),
/// "witness_wall_s": s}.
nlohmann::json ConvergenceJson(const Scene& scene, const ConvergenceCheck& check);

/// One plain-words sentence for the console and the report; empty when converged.
std::string ConvergenceWarning(const ConvergenceCheck& check);

}  // namespace rockbench
