#pragma once
/// Agreement of an engine's run with the reference model: angle errors on a common time grid
/// (the engine's sample times, the reference evaluated there by its dense output), agreement
/// horizon, peaks, impact sequence, overturning and final state. Writes comparison.json and
/// comparison.csv.
#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "reference/simulate.h"
#include "run/engine_run.h"
#include "run/tolerance.h"
#include "scene/scene.h"

namespace rockbench {

/// A block is judged point by point when the reference's peak |theta| of it is at least this
/// many times its tolerance floor (1% of its critical angle, or the scene's constant
/// tolerance): below, the tolerance is more than a fifth of the block's whole motion, so an
/// engine whose block never moves would stay within it (docs/verdicts.md, "Blocks below the
/// floor").
inline constexpr double kJudgedPeakOverFloor = 5.0;
/// A block not judged point by point is judged by its peak |theta|: the engine's must be within
/// kPeakToleranceRel of the reference's, and never less than kPeakToleranceFloorFraction of the
/// floor (0.1% of the critical angle: the tilt d / B of a corner moved by the monitor's
/// significant contact displacement d = 0.1% alpha B, which an engine's compliant contact
/// reaches; so a reference at rest and an engine tilting within its contacts agree).
inline constexpr double kPeakToleranceRel = 0.25;
inline constexpr double kPeakToleranceFloorFraction = 0.1;

/// Agreement of one body's compared angle (theta1, theta2, ..., thetaN of planar blocks) with
/// the reference.
struct AngleAgreement {
  /// The column stem of the quantity compared (scene/body_kind.h): "theta" for the planar block,
  /// "tilt_x" and "tilt_y" for the cylinder. Its keys and columns are BodyColumn(quantity, body).
  std::string quantity = "theta";
  /// Its name in comparison.json and the verdict's words when the body has several compared
  /// angles ("tilt_y1"); empty: BodyColumn(quantity, body) by the body's place.
  std::string name;
  /// The tolerance at the reference's peak (AngleTolerance_rad): the scale of the run's
  /// largest motion. The horizon uses the local tolerance (run/tolerance.h).
  double tolerance_rad = 0.0;
  double tolerance_min_rad = 0.0;         ///< the local tolerance's smallest value
  double tolerance_at_horizon_rad = 0.0;  ///< the local tolerance the error exceeded
  /// max over the compared samples of |error| / local tolerance (> 1: outside the tolerance),
  /// its time, and the same before the predictability horizon.
  double max_error_ratio = 0.0, max_error_ratio_t_s = 0.0, max_error_ratio_predictable = 0.0;
  double max_abs_error_rad = 0.0;          ///< max |theta_engine - theta_ref| over the compared run
  double rms_error_rad = 0.0;              ///< RMS of the same over the compared run
  double horizon_s = 0.0;                  ///< first time the error exceeds the local tolerance
                                           ///< (the end of the comparison if it never does)
  bool within_tolerance = true;            ///< the error never exceeded the tolerance
  double max_abs_error_horizon_rad = 0.0;  ///< max error before the horizon
  double rms_error_horizon_rad = 0.0;      ///< RMS error before the horizon
  double peak_reference_rad = 0.0, peak_reference_t_s = 0.0;  ///< peak |theta| and its time
  double peak_engine_rad = 0.0, peak_engine_t_s = 0.0;
  double peak_rel_error = 0.0;     ///< (peak_engine - peak_ref) / peak_ref (0 if ref is 0)
  double peak_time_error_s = 0.0;  ///< peak_engine_t - peak_ref_t
  /// The same errors split at the reference's predictability horizon (CompareOptions): where
  /// the reference is predictable an error is the engine's; beyond it, the problem's own
  /// sensitivity is part of it. Zero with no sample on that side.
  double max_abs_error_predictable_rad = 0.0, rms_error_predictable_rad = 0.0;
  double max_abs_error_beyond_rad = 0.0, rms_error_beyond_rad = 0.0;
  int samples_beyond = 0;
  /// The horizon used for that split (+inf: predictable to the end, or no perturbation members were
  /// run).
  double predictability_horizon_s = std::numeric_limits<double>::infinity();
  /// The tolerance's floor (1% of the critical angle, or the scene's constant tolerance), rad.
  double floor_rad = 0.0;
  /// Whether the block is judged point by point: the reference's peak is at least
  /// kJudgedPeakOverFloor times the floor. When not, its peak decides instead:
  /// |peak_engine - peak_reference| within peak_tolerance_rad (max(kPeakToleranceRel x the
  /// reference's peak, kPeakToleranceFloorFraction x the floor)).
  bool judged = true;
  double peak_tolerance_rad = 0.0;
  bool peak_within_tolerance = true;
  /// Impacts of this block (block 1 on the ground, block k on block k - 1) in each run, faster
  /// than the comparison's minimum rate, over the compared run (reported beside the peak).
  int impacts_reference = 0, impacts_engine = 0;
  /// Engine minus reference at the last compared sample, rad: set for a body's more_angles (its
  /// first angle's is BodyAgreement::final_angle_error_rad).
  double final_error_rad = 0.0;
};

/// Agreement of one block's slip u_k (or lift z_k) on its support with the reference's, where
/// both histories carry them (docs/sliding.md). The tolerance is on the slip's own scale:
/// 10% of the reference's peak |u_k| over the run, never below 1% of the block's critical
/// angle times its width (alpha_k B_k: ten times the monitor's significant displacement). The
/// error that decides is the engine's distance from the range the reference's value takes
/// within two output intervals of the time (time_slack_s): a slip episode a few ms early is a
/// timing difference, not a slip of another size (docs/verdicts.md).
struct SlipAgreement {
  std::string quantity = "u";  ///< the column stem: "u" (slip) or "z" (lift)
  double tolerance_m = 0.0, floor_m = 0.0;
  double peak_reference_m = 0.0, peak_reference_t_s = 0.0;  ///< max |u_ref| over the run
  double peak_engine_m = 0.0;                               ///< max |u_engine|, compared run
  double max_abs_error_m = 0.0, rms_error_m = 0.0;          ///< over the compared run
  /// The error with the time slack (what the tolerance judges), m, and the slack, s.
  double max_abs_error_slack_m = 0.0, time_slack_s = 0.0;
  /// Before the block's predictability horizon (that of its angle), with the time slack: there
  /// an error decides.
  double max_abs_error_predictable_m = 0.0;
  double max_error_ratio_predictable = 0.0;  ///< max |error| / tolerance there
  bool within_tolerance = true;              ///< the error never exceeded the tolerance
  double horizon_s = 0.0;  ///< first time it did (the end of the comparison if never)
  double final_reference_m = 0.0, final_engine_m = 0.0;  ///< at the last compared sample
  double predictability_horizon_s = std::numeric_limits<double>::infinity();
  /// Within the tolerance wherever the reference is predictable.
  bool agrees_predictable() const { return !(max_error_ratio_predictable > 1.0); }
};

/// The engine's impacts against the reference's, matched in order until the first missing or
/// extra impact. An engine impact matches the next reference impact when it is of the same
/// kind and closer to it than half the gap to the neighbouring reference impacts (clamped to
/// [2 ms, 0.25 s]). Impacts slower than CompareOptions::min_impact_rate_radps are left out of
/// both lists; an unmatched impact slower than twice that ("marginal": the other run may have
/// seen it just below the minimum) is skipped instead of ending the match.
struct ImpactAgreement {
  int reference_impacts = 0;  ///< compared (landing rate >= the option's minimum)
  int engine_impacts = 0;
  int reference_impacts_all = 0;  ///< all, the slow ones included
  int engine_impacts_all = 0;
  int matched = 0;
  int skipped_marginal = 0;           ///< unmatched marginal impacts passed over
  std::vector<double> time_errors_s;  ///< engine - reference, per matched impact
  double max_abs_time_error_s = 0.0;  ///< over the matched impacts
  std::string first_mismatch;         ///< empty when every impact of both runs matched
};

/// kMaxBlocks times +inf.
inline constexpr std::array<double, kMaxBlocks> EveryBlockInfinite() {
  std::array<double, kMaxBlocks> a{};
  for (double& v : a) v = std::numeric_limits<double>::infinity();
  return a;
}

/// Everything compared of one body (body k of the stack at index k - 1 of
/// EngineAgreement::bodies).
struct BodyAgreement {
  /// The body's first compared angle (theta_k of a planar block, tilt_xk of a cylinder).
  AngleAgreement angle;
  /// Engine minus reference of the compared angle at the last compared sample, rad.
  double final_angle_error_rad = 0.0;
  /// Its slip u_k and lift z_k on its support, when both histories carry them.
  std::optional<SlipAgreement> slip, lift;
  /// Its further compared angles, named (AngleAgreement::name): a cylinder's tilt_yk (the tilt
  /// vector's two components, judged each on the tilt's local tolerance). Empty for the planar
  /// block.
  std::vector<AngleAgreement> more_angles;
};

/// Options of the comparison.
struct CompareOptions {
  /// Per block (block k at k - 1), the reference's predictability horizon (s): errors are also
  /// reported separately before it and after it. +inf: the reference is predictable to the end.
  std::array<double, kMaxBlocks> predictability_horizon_s = EveryBlockInfinite();
  /// Impacts whose landing rate (|omega1| before a ground impact, |omega2 - omega1| before an
  /// interface impact) is below this are not compared, in either run: they are the tails of
  /// the cascades with which a rocking block settles, and an engine monitor that sees a tilt
  /// only above 1e-5 rad cannot resolve them (rad/s).
  double min_impact_rate_radps = 0.02;
};

/// Everything known about one engine's agreement with the reference.
struct EngineAgreement {
  std::string engine;
  double wall_s = 0.0;
  RunStatus status = RunStatus::kCompleted;  ///< the engine's status (summary "status")
  std::string status_detail;                 ///< and its detail (summary "status_detail")
  /// Status non_finite (run/engine_run.h): what stopped being finite ("energy is +inf") and
  /// when, s (summary "non_finite"); the comparison ends at the run's last finite state.
  std::string non_finite_what;
  double non_finite_t_s = 0.0;
  double compared_until_s = 0.0;  ///< end of the common grid
  int samples_compared = 0;
  /// Per body, body k at index k - 1: its angle, final error, slip and lift.
  std::vector<BodyAgreement> bodies;
  ImpactAgreement impacts;
  /// A block that left its support (slid off it): both runs or neither, and the same block.
  bool left_support_agree = true;
  std::optional<int> left_support_block_reference, left_support_block_engine;
  std::optional<double> left_support_time_error_s;
  /// Overturning: both or neither, and the same block.
  bool overturn_agree = true;
  std::optional<int> overturn_block_reference, overturn_block_engine;
  std::optional<double> overturn_time_error_s;
  /// A cylinder's fall: the azimuth toward which each run's top fell (rad, from +x toward +y,
  /// within (-pi, pi]); absent for planar blocks and for a run that did not overturn.
  std::optional<double> overturn_azimuth_reference_rad, overturn_azimuth_engine_rad;
  /// Final state at compared_until_s: same mode family (rest / rocking / overturned) and angles
  /// within the horizon tolerances.
  bool final_agree = true;
  std::string final_mode_reference, final_mode_engine;
  nlohmann::json violations;  ///< the engine's summary "violations" (null when it has none)
  /// The engine's monitor flags (kViolationFlags) and when each was first raised, s.
  std::vector<std::string> flags;
  std::vector<double> flag_onsets_t_s;
  /// The same at the verdict's scale (RunOutcome::significant_violations): these decide.
  std::vector<std::string> significant_flags;
  std::vector<double> significant_onsets_t_s;
  /// The reference's status and where its solution ends (s): past an "assumption_violated"
  /// end the model has nothing to say; past a "non_finite" end nothing was computed.
  RunStatus reference_status = RunStatus::kCompleted;
  std::string reference_status_detail;
  double reference_end_s = 0.0;
  /// The reference's first impact with no admissible outcome or several (Summary::
  /// undetermined_from_s): from there its motion is a choice of the rule, not the model's.
  std::optional<double> reference_undetermined_s;
  std::string reference_undetermined_detail;
  /// Reference status non_finite: what stopped being finite and when, s.
  std::string reference_non_finite_what;
  double reference_non_finite_t_s = 0.0;
  /// The verdict (compare/verdict.h), when one was made: its kind, whether the engine agrees,
  /// the plain-words text and the statistical comparison (engines.<name>.statistics).
  std::string verdict_kind, verdict;
  bool verdict_agrees = false;
  std::string verdict_decided_by;  ///< the quantity that decided the verdict, with its value
  nlohmann::json seeds;            ///< the seeds' decisions when the verdict was re-seeded
  nlohmann::json statistics;

  /// Bodies compared.
  int blocks() const { return static_cast<int>(bodies.size()); }
  /// Body `block`'s agreement (1..blocks()).
  const BodyAgreement& body(int block) const { return bodies.at(static_cast<size_t>(block - 1)); }
  BodyAgreement& body(int block) { return bodies.at(static_cast<size_t>(block - 1)); }
  /// Body `block`'s compared angle (1..blocks()).
  const AngleAgreement& angle(int block) const { return body(block).angle; }
  AngleAgreement& angle(int block) { return body(block).angle; }
  /// Every compared angle: each body's `angle` and then its `more_angles`, body 1 first (one
  /// per body for planar blocks; tilt_x1, tilt_y1 for a cylinder). The verdict judges these,
  /// in this order (Horizons holds one horizon per entry).
  std::vector<const AngleAgreement*> compared_angles() const;
};

/// Impacts of a history whose landing rate (|omega1| before a ground impact, |omega_k -
/// omega_(k-1)| before an interface impact of block k) is at least `min_rate_radps`: the impacts a
/// comparison counts.
int CountComparedImpacts(const History& history, double min_rate_radps);

/// The largest |value| of body `block` (0-based) read by `angle` over a history's samples up to
/// until_s, and its time (0 and 0 when no sample is that early).
void SampledPeak(const History& h, const StateQuantityReader& angle, int block, double until_s,
                 double* peak, double* t);

/// Whether block `block`'s peak agrees with the reference's on the scale of a block below the
/// floor: |peak_engine - peak_reference| <= max(kPeakToleranceRel peak_reference,
/// kPeakToleranceFloorFraction floor). Sets *tolerance_rad to that bound.
bool PeakAgrees(double peak_reference_rad, double peak_engine_rad, double floor_rad,
                double* tolerance_rad);

/// The tolerance of a block's slip (or lift): max(0.1 peak_reference, 0.01 alpha B), m.
double SlipTolerance_m(const Scene& scene, int block, double peak_reference_m);

/// Copies an engine run's name, wall time, status (its detail, what stopped being finite and
/// when) and monitor flags (all and significant, with their onsets) into `a`.
void CopyEngineRunStatus(const EngineRun& run, EngineAgreement* a);

/// Compares an engine's run with the reference's result on the same scene.
EngineAgreement CompareWithReference(const Scene& scene, const reference::Result& reference,
                                     const EngineRun& run, const CompareOptions& options = {});

/// comparison.json: {"scene": ..., "reference": {...}, "engines": {name: {...}}}. Keys read by
/// other tools: engines.<name>.wall_s, engines.<name>.impacts_matched and, under
/// engines.<name>.theta1 ... thetaN (BodyColumn(quantity, k) of each body k): max_abs_error_rad,
/// rms_error_rad, peak_rel_error, peak_time_error_s, horizon_s, judged; engines.<name>.u1 ..
/// uN and z1 .. zN (histories with slip and lift): max_abs_error_m, final_reference_m,
/// final_engine_m, tolerance_m; engines.<name>.left_support.
nlohmann::json ComparisonJson(const Scene& scene, const reference::Result& reference,
                              double reference_wall_s, const std::vector<EngineAgreement>& engines,
                              const CompareOptions& options = {});

/// comparison.csv: a header and one row per engine and block.
std::string ComparisonCsv(const std::vector<EngineAgreement>& engines);

/// One agreement as JSON (the value under engines.<name> in comparison.json).
nlohmann::json AgreementJson(const EngineAgreement& a);

}  // namespace rockbench
