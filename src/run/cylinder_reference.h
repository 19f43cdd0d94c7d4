#pragma once
/// The reference's run of a cylinder scene (shape "cylinder", reference/cylinder_run.h) behind
/// the engine interface: the nominal run and its witness (the other Dormand-Prince pair at a
/// hundredth of the tolerances, run/reference_witness.h's rule), compared on the tilt vector
/// (tilt_x, tilt_y); the witness is used when the two differ by more than the comparison's
/// tolerance at the reference's peak tilt.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "engine/engine.h"
#include "reference/cylinder_run.h"

namespace rockbench {

/// The cylinder reference's extension of its EngineResult.
struct CylinderReferenceExtension : EngineResultExtension {
  reference::cylinder::CylinderResult nominal;
  double nominal_wall_s = 0.0;
  std::optional<reference::cylinder::CylinderResult> witness;
  double witness_wall_s = 0.0;
  /// The largest |tilt vector difference| between the two on the output times both reached,
  /// rad, and the tolerance it is held to (AngleTolerance_rad at the nominal peak tilt).
  double max_abs_diff_rad = 0.0, tolerance_rad = 0.0;
  bool same_status = true;
  bool converged() const { return !witness || (max_abs_diff_rad <= tolerance_rad && same_status); }
  const reference::cylinder::CylinderResult& used() const {
    return converged() || !witness ? nominal : *witness;
  }
};

/// Runs the cylinder reference (and its witness when options.check_convergence).
EngineResult SimulateCylinderReference(const Scene& scene, const GroundMotion& motion,
                                       const SimulateOptions& options);

/// summary.json of a cylinder reference run: status, peak tilt, landings, overturn (time and
/// azimuth), the landing rule, the rim's friction and normal force, convergence.
nlohmann::json CylinderSummaryJson(const Scene& scene, const CylinderReferenceExtension& run);

/// "reference: completed, peak tilt 0.1 rad at 0.000 s, 3 landings, 1.2 ms".
std::string CylinderSummaryLine(const CylinderReferenceExtension& run);

}  // namespace rockbench
