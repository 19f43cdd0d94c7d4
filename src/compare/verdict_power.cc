#include "compare/verdict_power.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "reference/simulate.h"
#include "run/parallel.h"
#include "run/summary.h"

namespace rockbench {
namespace {

double MinHolm(const StatisticalComparison& s) {
  double p = std::numeric_limits<double>::infinity();
  for (const QuantityComparison& q : s.quantities) {
    if (!std::isnan(q.p_holm)) p = std::min(p, q.p_holm);
  }
  if (!std::isnan(s.overturn_p_holm)) p = std::min(p, s.overturn_p_holm);
  return p;
}

}  // namespace

PowerEstimate EstimateVerdictPower(const Scene& scene, const GroundMotion& motion,
                                   const PowerConfig& config) {
  const CompareOptions compare_options;
  // The scene's tolerances, one per block, from its nominal run.
  const reference::Result nominal = reference::Simulate(scene, motion);
  std::vector<double> tolerance;
  for (int b = 0; b < scene.block_count(); ++b) {
    tolerance.push_back(AngleTolerance_rad(scene, b + 1, nominal.summary.peak_theta_rad[b]));
  }
  const int n = config.reference_members, m = config.engine_members;
  PowerEstimate est;
  est.trials = config.trials;
  for (int k = 0; k < config.trials; ++k) {
    Scene s = scene;
    s.compare.seed = config.first_seed + static_cast<uint64_t>(k);
    std::vector<MemberOutcome> outcomes(n + m);
    ParallelFor(n + m, config.threads, [&](int i) {
      const MemberInput in = PerturbedInput(s, motion, i);
      reference::Result r = reference::Simulate(in.scene, in.motion);
      EngineRun run;
      run.engine = "reference";
      run.summary = ReferenceSummaryJson(in.scene, r, 0.0);
      run.outcome = ReferenceOutcome(r);
      run.history = std::move(r.history);
      outcomes[i] = OutcomeOf(run, in.scene, compare_options.min_impact_rate_radps);
      outcomes[i].member = i;
    });
    const std::vector<MemberOutcome> reference(outcomes.begin(), outcomes.begin() + n);
    // The engine's members are numbered 0 .. M-1 for ComparePerturbationMembers' pairing (every
    // reference member it pairs with must be valid for the engine member to count).
    std::vector<MemberOutcome> unbiased(outcomes.begin() + n, outcomes.end());
    for (int i = 0; i < m; ++i) unbiased[i].member = i;
    std::vector<MemberOutcome> biased = unbiased;
    for (MemberOutcome& o : biased) {
      for (double& p : o.peak_rad) p *= 1.0 + config.bias;
    }
    const StatisticalComparison sb =
        ComparePerturbationMembers(reference, biased, tolerance, scene.run.output_interval_s);
    const StatisticalComparison su =
        ComparePerturbationMembers(reference, unbiased, tolerance, scene.run.output_interval_s);
    if (sb.available && !sb.consistent) ++est.detected_biased;
    if (su.available && !su.consistent) ++est.flagged_unbiased;
    est.min_p_biased.push_back(MinHolm(sb));
    est.min_p_unbiased.push_back(MinHolm(su));
  }
  return est;
}

}  // namespace rockbench
