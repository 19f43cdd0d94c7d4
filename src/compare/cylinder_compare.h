#pragma once
/// The comparison of a cylinder (shape "cylinder", docs/three-d.md) with its reference: the
/// same judgement as a planar block's (docs/verdicts.md), on the tilt vector.
///
/// - Point by point: tilt_x and tilt_y (the tilt vector's components, continuous through
///   upright) at every engine sample against the reference's history interpolated there, each
///   on the local tolerance of the tilt (run/tolerance.h: 10% of the largest tilt within two
///   rocking periods, at least 1% of atan(D / H)).
/// - The predictability horizon: the reference's perturbation members (the three components'
///   amplitudes, the records' samples, the initial tilt and rates) and the first time their
///   tilt vectors spread from the nominal one by more than the tolerance at the peak tilt.
/// - Beyond it: the engine's members against the reference's on the peak tilt, its time, the
///   RMS and residual tilt, overturning and the fall's azimuth (compare/verdict.h).
#include <optional>

#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "reference/cylinder_run.h"
#include "run/cylinder_reference.h"
#include "run/engine_run.h"
#include "scene/scene.h"

namespace rockbench {

/// The reference's tilt vector (tilt_x, tilt_y) at t_s, rad: its history's samples (the output
/// grid and every event) interpolated linearly, held at its last sample after its end.
struct TiltVector {
  double x_rad = 0.0, y_rad = 0.0;
};
TiltVector TiltVectorAt(const History& history, double t_s);

/// The azimuth toward which a cylinder run's top fell (summary.json overturn.azimuth_rad, rad),
/// if it overturned.
std::optional<double> FallAzimuthOf(const EngineRun& run);

/// Compares an engine's cylinder run with the reference's solution `reference` (the one used:
/// CylinderReferenceExtension::used()). Body 1's `angle` is tilt_x1, its more_angles {tilt_y1};
/// the impacts are not matched (a cylinder's landings and its passes near upright are counted
/// in each summary); overturning compares the fall's azimuth too.
EngineAgreement CompareCylinderWithReference(const Scene& scene,
                                             const reference::cylinder::CylinderResult& reference,
                                             const EngineRun& run,
                                             const CompareOptions& options = {});

/// Runs `members` perturbation members of the cylinder reference with the model settings of
/// `nominal_scene` and measures the spread of their tilt vectors around `nominal`'s on the
/// output grid: the horizon is the first grid time where it exceeds `tolerance_rad` (the
/// tolerance at the nominal peak tilt), where a member's model ends (lift-off, slip) while the
/// nominal's goes on, or where the nominal's ends. The result's stem is "tilt", its one
/// "block" the cylinder.
ReferencePerturbationMembers RunCylinderPerturbationMembers(
    const Scene& nominal_scene, const GroundMotion& motion,
    const reference::cylinder::CylinderResult& nominal, int members, double tolerance_rad,
    int threads);

/// comparison.json of a cylinder scene: scene, reference (status, peak tilt, landings,
/// overturn), tolerance (the rule, tilt_x1_rad and tilt_y1_rad at the peak tilt),
/// engines.<name> (AgreementJson).
nlohmann::json CylinderComparisonJson(const Scene& scene,
                                      const reference::cylinder::CylinderResult& reference,
                                      double reference_wall_s,
                                      const std::vector<EngineAgreement>& engines);

}  // namespace rockbench
