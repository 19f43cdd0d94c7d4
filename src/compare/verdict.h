#pragma once
/// An engine's verdict: what part of its difference from the reference is the engine's and what
/// part is the problem's own sensitivity.
///
/// 1. Where the reference is predictable (before its predictability horizon), the engine must
///    stay within the comparison tolerance of the reference: an error there is the engine's.
/// 2. Beyond the horizon, runs whose inputs differ within what the inputs are known to spread by
///    more than the tolerance, so one run's error ranks nothing: the engine's perturbation members
///    (the same perturbed inputs) is compared with the reference's by two-sample tests on what a
///    user cares about (peaks, time of the largest excursion, impacts, residual angle,
///    overturning), Holm- adjusted as one family at alpha = 0.05.
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "statistics/statistics.h"

namespace rockbench {

/// One quantity's two-sample comparison.
struct QuantityComparison {
  std::string key;    ///< "peak_theta1_rad", "peak_theta1_t_s", "impacts", "residual_theta1_rad"
  std::string label;  ///< "peak |theta1|", ...
  std::string unit;   ///< "rad", "s", ""
  /// The quantity's resolution: differences of value smaller than this are not differences
  /// (the slack of the Kolmogorov-Smirnov test, stats::KolmogorovSmirnovSlackTest).
  double margin = 0.0;
  std::vector<double> reference, engine;  ///< the samples
  stats::TestResult ks;                   ///< KS with the margin as slack: the verdict's test
  stats::TestResult ad;                   ///< Anderson-Darling (no slack), reported beside KS
  double p_holm = 1.0;                    ///< KS p-value, Holm-adjusted over the family
  /// Whether the quantity is in the Holm family that decides the verdict; the impact count is
  /// reported beside it only (its value depends on its rate threshold: docs/verdicts.md).
  bool in_family = true;
};

/// The engine's perturbation members against the reference's.
struct StatisticalComparison {
  bool available = false;
  std::string unavailable_reason;  ///< when not available
  int reference_members = 0, engine_members = 0;
  /// Members whose reference run violated the model's assumptions or ended non_finite (no
  /// reference outcome); of them, non_finite.
  int excluded = 0, excluded_non_finite = 0;
  /// Engine members that ended non_finite: the engine failed on them (the verdict is
  /// violates_model); the first one's member index and detail.
  int engine_non_finite = 0;
  std::string engine_non_finite_detail;
  double alpha = 0.05;
  std::vector<QuantityComparison> quantities;
  /// Blocks compared (the per-block quantities and the overturning categories).
  int blocks = 1;
  /// Overturning: counts of none / block 1 / block 2 / ... / block N (at index N) in each set
  /// of perturbation members, Fisher-Freeman-Halton.
  std::array<int, kMaxBlocks + 1> overturn_reference{}, overturn_engine{};
  stats::TestResult overturn;
  double overturn_p_holm = 1.0;
  bool consistent = true;             ///< no Holm-adjusted p-value at or below alpha
  std::vector<std::string> rejected;  ///< keys of the quantities that differ
};

/// Compares the engine's member outcomes with the reference's. `tolerance_rad`: the comparison
/// tolerances, one per block of the stack (they set the angle margins: 10% of them; their
/// number is the number of blocks compared); `time_margin_s`: the margin of times (the scene's
/// output interval). Per block k (thetak): peak_thetak_rad, peak_thetak_t_s, rms_thetak_rad,
/// residual_thetak_rad, in that order of quantities, then the overturning (none or which
/// block), one Holm family. `stem` names the compared magnitude in the keys: "theta" for planar
/// blocks, "tilt" for a cylinder (whose members also compare their fall azimuth,
/// fall_azimuth1_rad, when at least five overturned on each side).
StatisticalComparison ComparePerturbationMembers(const std::vector<MemberOutcome>& reference,
                                                 const std::vector<MemberOutcome>& engine,
                                                 std::span<const double> tolerance_rad,
                                                 double time_margin_s, double alpha = 0.05,
                                                 std::string_view stem = "theta");

/// The verdict on one engine.
struct Verdict {
  /// "agrees" (pointwise over the whole run, or to the horizon and statistically beyond it),
  /// "agrees_to_horizon" (no statistical comparison was made beyond it),
  /// "differs_before_horizon" (an engine error where the reference is predictable, on the
  /// local tolerance, or an overturn the reference does not make),
  /// "differs_beyond_horizon" (the engine's perturbation members differs from the reference's),
  /// "violates_model" (the engine's run ended non_finite, decided by "non_finite at t = ...";
  /// or it blew up or gained energy, or slid, lifted or penetrated where the reference's model
  /// holds; or a member of its perturbation members ended non_finite),
  /// "reference_failed" (the reference's solution, or a member of its perturbation members, ended
  /// non_finite: there is nothing to compare with, and the comparison failed),
  /// "outside_model" (the reference stops where its assumptions end: nothing to compare),
  /// "marginal" (the statistical decision changes with the members' seed),
  /// "pointwise_only" / "pointwise_differs" (no perturbation members were run).
  std::string kind;
  bool agrees = false;
  std::string text;        ///< one paragraph in plain words
  std::string decided_by;  ///< the quantity that decided, with its value
};

/// The console's word for a verdict kind: AGREES, DIFFERS, MARGINAL, OUTSIDE MODEL or NO VERDICT
/// (reference_failed).
std::string VerdictLabel(const std::string& kind);

/// The smallest Holm-adjusted p-value of the family (the overturning test included).
double SmallestFamilyP(const StatisticalComparison& s);

/// Seeds a statistical decision is checked with when its smallest p-value is in the marginal
/// band (the scene's seed and the next ones).
inline constexpr int kVerdictSeeds = 3;
/// The marginal band of the smallest Holm-adjusted p-value, [alpha / 10, 4 alpha] at alpha =
/// 0.05: measured seed-to-seed, a p-value moves by up to a factor of ~10 (docs/verdicts.md).
inline constexpr double kMarginalLowP = 0.005, kMarginalHighP = 0.2;
inline bool InMarginalBand(double p) {
  return p >= kMarginalLowP && p <= kMarginalHighP;
}

/// Horizons per compared angle, in EngineAgreement::compared_angles()'s order (per block, block
/// k at k - 1, for planar blocks; tilt_x1 and tilt_y1, both the tilt vector's horizon, for a
/// cylinder): nullopt inside means "predictable for the whole run";
/// an absent `predictability` means no perturbation members were run.
struct Horizons {
  std::array<std::optional<double>, kMaxBlocks> horizon_s{};
  /// Reference members that ended non_finite (run/engine_run.h), and the first one's
  /// "member i: detail": the horizon measured without them is not the reference's, and the
  /// verdict is reference_failed.
  int non_finite_members = 0;
  std::string non_finite_detail;
};

Verdict MakeVerdict(const Scene& scene, const EngineAgreement& agreement,
                    const std::optional<Horizons>& predictability,
                    const std::optional<StatisticalComparison>& statistics);

/// comparison.json engines.<name>.statistics.
nlohmann::json StatisticsJson(const StatisticalComparison& s);

}  // namespace rockbench
