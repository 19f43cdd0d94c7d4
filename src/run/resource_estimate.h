#pragma once
/// What a run will need, estimated from its scene before anything is allocated or simulated,
/// and checked against the command's budget (docs/limits.md gives the measured figures behind
/// each term). The estimate is an upper bound of the usual case, not a promise: the wall-clock
/// limit (--wall-limit) stops what it misjudges.
#include <string>
#include <vector>

#include "scene/limits.h"
#include "scene/scene.h"

namespace rockbench {

/// One term of an estimate: the scene key that sets it and what it counts.
struct EstimateTerm {
  std::string key;   ///< "run.output_interval", "model.step", "bullet.time_step", ...
  std::string what;  ///< "2e+09 history rows of 256 B", ...
  double bytes = 0.0;
  double cpu_s = 0.0;
};

/// The estimate of a command on one scene.
struct RunEstimate {
  std::vector<EstimateTerm> terms;
  double bytes = 0.0;   ///< peak memory, bytes
  double cpu_s = 0.0;   ///< CPU time, s
  double wall_s = 0.0;  ///< cpu_s spread over the worker threads, s
  /// A run that cannot be made whatever the budget ("KEY: why"): an external engine's step
  /// whose input would hold more than external::kMaxInputSteps rows of base motion. Empty:
  /// none.
  std::string refusal;
  /// The term with the most bytes and the one with the most CPU time.
  const EstimateTerm* largest_bytes() const;
  const EstimateTerm* largest_cpu() const;
};

/// What a run of the reference and `engines` (engine names; "reference" among them adds nothing:
/// the reference is always counted) with `members` reference and
/// `engine_members` engine perturbation members on `jobs` threads needs. The engines' steps come
/// from their tables' time_step (resolved against their schemas; a scene whose table does not
/// resolve is left to the engine's own error). An engine's CPU time per step grows with the
/// blocks n as (n / 2)^p, p measured per engine (resource_estimate.cc, docs/limits.md). Throws
/// nothing for a valid scene.
RunEstimate EstimateRun(const Scene& scene, const std::vector<std::string>& engines, int members,
                        int engine_members, int jobs);

/// Throws SceneError naming the scene file, the largest term's key and the estimate when the
/// estimate exceeds the budget (memory; wall time against budget.wall_s), and the refusal when
/// there is one.
void CheckRunEstimate(const RunEstimate& estimate, const ResourceBudget& budget,
                      const std::string& where);

}  // namespace rockbench
