#pragma once
/// The whole comparison `rockbench compare` makes, in process: the reference checked against its
/// witness, the reference's perturbation members (predictability horizon), each engine's run and,
/// where the horizon falls inside the run, its perturbation members and the statistical comparison;
/// then one verdict per engine. Used by the CLI and by the agreement suite.
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "compare/verdict.h"
#include "run/cylinder_reference.h"
#include "run/engine_run.h"
#include "run/reference_engine.h"

namespace rockbench {

struct CompareRunOptions {
  int jobs = 0;  ///< threads for the perturbation members (0: every hardware thread)
  /// Called with one line of progress text as each stage ends (the CLI prints them).
  std::function<void(const std::string&)> log;
};

/// An engine whose run could not be made or compared (its program exited non-zero, could not
/// reserve memory, its settings were refused): its own verdict, the other engines' stand.
struct FailedEngine {
  std::string engine;
  std::string reason;  ///< one line: the error's message
};

struct CompareRun {
  /// The reference's own result, from reference_run's extension (no copy).
  const CheckedReference& reference() const {
    return *ReferenceResultOf(reference_run.extension.get());
  }
  /// A cylinder scene's reference (docs/three-d.md), from reference_run's extension; null for
  /// planar blocks (whose reference() this is not).
  const CylinderReferenceExtension* cylinder_reference() const {
    return dynamic_cast<const CylinderReferenceExtension*>(reference_run.extension.get());
  }
  Scene reference_scene;  ///< the scene with the model settings of the solution used
  /// Per block (AngleTolerance_rad of the reference; a cylinder's at its peak tilt).
  std::vector<double> tolerance_rad;
  std::optional<ReferencePerturbationMembers>
      perturbation_members;  ///< none with compare.members = 0
  /// Nominal runs, in the order asked, of the engines that did not fail (engine_runs[k].engine
  /// names each; agreements and engine_outcomes follow the same order).
  std::vector<EngineRun> engine_runs;
  /// The engines that failed, in the order asked (comparison.json "failed_engines"). Not empty:
  /// the comparison is incomplete (`rockbench compare` writes the others and exits with
  /// kExitRunFailed).
  std::vector<FailedEngine> failed_engines;
  /// Per engine: its perturbation members' outcomes (empty when none was run).
  std::vector<std::vector<MemberOutcome>> engine_outcomes;
  std::vector<EngineAgreement> agreements;  ///< with their verdicts
  nlohmann::json comparison;                ///< comparison.json
  /// The reference's run as written to DIR/reference (history of the solution used; summary
  /// with "convergence").
  EngineRun reference_run;
  /// Every run of the comparison that ended non_finite (run/engine_run.h), one line each
  /// ("reference: theta2 is NaN at t = ...", "bullet perturbation member 3: ..."): the reference
  /// (the solution used), the engines, and the members of the perturbation members. Not empty: the
  /// comparison failed (`rockbench compare` exits with kExitRunFailed).
  std::vector<std::string> failures;
};

/// Runs the comparison of `engines` (names from AvailableEngines, "reference" excluded) on a
/// scene. Throws SceneError for impossible settings and when the reference cannot run; an
/// engine that throws (std::exception, std::bad_alloc included) is a FailedEngine.
CompareRun RunCompare(const Scene& scene, const GroundMotion& motion,
                      const std::vector<std::string>& engines,
                      const CompareRunOptions& options = {});

}  // namespace rockbench
