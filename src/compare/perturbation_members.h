#pragma once
/// Perturbation members: runs on perturbed inputs: what the problem itself does when its inputs
/// move within what they are known to. Member i's inputs depend only on ([compare] seed, i), so
/// engine member i sees exactly the inputs of reference member i.
///
/// - The reference's perturbation members gives the predictability horizon: per block, the first
/// time the
///   members spread from the nominal run by more than the comparison tolerance.
/// - Member outcomes (peaks, overturning, time of the largest excursion, impacts, residual
///   angle) are what the statistical comparison beyond the horizon is made of.
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_run.h"
#include "scene/scene.h"

namespace rockbench {

/// How member i's inputs differ from the nominal ones (factors are 1 + u * size, u in [-1, 1]).
struct MemberPerturbation {
  int member = 0;
  double horizontal_factor = 1.0;  ///< amplitude factor of base.horizontal
  double vertical_factor = 1.0;    ///< amplitude factor of base.vertical
  /// Largest sample move of each record, m/s^2 (0 for analytic motions).
  double horizontal_max_sample_move_mps2 = 0.0, vertical_max_sample_move_mps2 = 0.0;
  /// Per body (body k at k - 1): the factors of its initial angle and rate, body 1's absolute,
  /// every other body's relative to the body below (theta_k - theta_(k-1), omega_k -
  /// omega_(k-1)). Empty for a member left unperturbed.
  std::vector<double> theta_factor, omega_factor;
  /// A 3-D scene's transverse component (base.transverse): its amplitude factor and largest
  /// sample move, m/s^2.
  double transverse_factor = 1.0;
  double transverse_max_sample_move_mps2 = 0.0;
  /// A cylinder's initial state: the factors of its tilt and of its tilt, azimuth and spin
  /// rates (the azimuth itself is not perturbed: a turned start is a turned problem, the
  /// rotation invariance of docs/three-d.md).
  double tilt_factor = 1.0, tilt_rate_factor = 1.0, azimuth_rate_factor = 1.0,
         spin_rate_factor = 1.0;
};

/// A member's scene and base motion.
struct MemberInput {
  MemberPerturbation perturbation;
  Scene scene;
  GroundMotion motion;
};

/// The output grid the members are measured on: t_k = k * run.output_interval (rounded as the
/// files' times), k = 0 .. to the run's duration.
std::vector<double> OutputGrid_s(const Scene& scene);

/// Member i's inputs, from the nominal scene and motion and the [compare] perturbation sizes
/// (amplitude_rel, sample_precision, initial_rel, seed). Deterministic: depends only on the
/// nominal inputs, the sizes, the seed and i.
MemberInput PerturbedInput(const Scene& scene, const GroundMotion& motion, int member);

/// What a user cares about in one run.
struct MemberOutcome {
  int member = -1;
  RunStatus status = RunStatus::kCompleted;  ///< as in summary.json
  std::string detail;                        ///< summary.json's status_detail (why it ended so)
  int overturned_block = 0;                  ///< 0: none, 1..N
  double overturn_t_s = 0.0;                 ///< when overturned_block != 0
  /// A cylinder that overturned: the azimuth toward which its top fell (rad, within (-pi, pi]).
  std::optional<double> overturn_azimuth_rad;
  /// Per block (block k at k - 1; the entries beyond the scene's blocks are zero):
  std::array<double, kMaxBlocks> peak_rad{};  ///< peak |theta_k|
  std::array<double, kMaxBlocks> peak_t_s{};  ///< their times (the time of the largest excursion)
  int impacts = 0;                            ///< impacts at or above the comparison's minimum rate
  std::array<double, kMaxBlocks> residual_rad{};  ///< theta_k at the end of the run
  /// The root mean square of theta_k over the scene's duration (sqrt of the integral of
  /// theta^2 to the run's end, or to an overturn, over run.duration): the intensity of the
  /// whole response, which counts nothing and so has no counting threshold.
  std::array<double, kMaxBlocks> rms_rad{};
  double wall_s = 0.0;
  /// A run that stopped because the model's assumptions failed, or that ended non_finite
  /// (run/engine_run.h), has no outcome to compare.
  bool valid() const { return status != RunStatus::kAssumptionViolated && !IsNonFinite(status); }
};

/// The outcome of a run (reference or engine) of `scene`: summary "status", "peaks",
/// "overturn"; the history's last sample and impacts. A cylinder's (history shape "cylinder")
/// peak, residual and RMS are of its tilt, its impacts 0, and a fall carries its azimuth
/// (summary overturn.azimuth_rad); its peak's time is the first sample within a tenth of the
/// tolerance of the peak (the resolution the peak is compared at: a lossless wobble returns to
/// its peak tilt again and again). An overturned block's peak and residual
/// are model.overturn_angle (signed) and its peak time the overturn time: past the crossing an
/// angle says nothing more, and engines stop on the step after it.
MemberOutcome OutcomeOf(const EngineRun& run, const Scene& scene, double min_impact_rate_radps);

/// The reference's perturbation members and what it says about predictability.
/// Per block, block k at k - 1: one entry per block of the scene.
struct ReferencePerturbationMembers {
  int members = 0;
  int blocks = 1;  ///< blocks of the scene
  /// The magnitude whose spread is measured, as named in the files: "theta" (each planar
  /// block's angle) or "tilt" (a cylinder's tilt vector: the spread is |member - nominal| of
  /// (tilt_x, tilt_y), the band the tilt's).
  std::string stem = "theta";
  std::vector<MemberPerturbation> perturbations;
  std::vector<MemberOutcome> outcomes;
  /// On the grid t_k = k * run.output_interval (to the end of the run): the band every member
  /// and the nominal run span, and the largest |member - nominal|.
  std::vector<double> t_s;
  std::vector<std::vector<double>> lo_rad, hi_rad, spread_rad;
  /// The local tolerance of each block on the grid (run/tolerance.h), which judges an
  /// engine's error before the horizon.
  std::vector<std::vector<double>> local_tolerance_rad;
  /// The tolerance at the scale of the nominal run's peak (AngleTolerance_rad): the horizon is
  /// the first t_k at which spread_rad exceeds it; the statistics' margins are 10% of it.
  std::vector<double> tolerance_rad;
  std::vector<std::optional<double>> horizon_s;  ///< nullopt: within the tolerance throughout
  std::vector<double> max_spread_rad;
  double wall_s = 0.0;  ///< wall-clock time of all the members
};

/// Runs `members` reference members with the model settings of `nominal_scene` (pass the scene
/// whose model produced `nominal`, e.g. the witness's when the default was not converged) and
/// measures their spread around `nominal`. `tolerance_rad`: per block, at least one entry per
/// block of the scene.
ReferencePerturbationMembers RunReferencePerturbationMembers(
    const Scene& nominal_scene, const GroundMotion& motion, const reference::Result& nominal,
    int members, std::span<const double> tolerance_rad, int threads, double min_impact_rate_radps);

/// The time (s) after which the base motion can no longer start rocking from rest: the last time
/// at which `safety` times the base acceleration (the vertical part taken at its worst sign)
/// would open a face of the stack at rest (a corner force of block 1 on the ground or of a
/// block on the one below turning tensile; N >= 3 blocks: the pivot chain's rest reactions,
/// reference/stack_contacts.h). Records are piecewise linear and the rest reactions linear in
/// the accelerations, so their sample times decide (a face open at one sample may be open
/// until the next: that is the bound); analytic motions are scanned every 1e-3 s. 0: never;
/// infinity for an endless motion. An engine member at rest after this time
/// has its outcome decided and can stop (SimulateOptions::stop_at_rest_after_s).
double SettledAfter_s(const Scene& scene, const GroundMotion& motion, double safety = 1.25);

/// Runs engine `name` on members 0 .. members-1 (the first reference members' inputs); each
/// stops once at rest after SettledAfter_s of its own inputs.
std::vector<MemberOutcome> RunEnginePerturbationMembers(const std::string& name, const Scene& scene,
                                                        const GroundMotion& motion, int members,
                                                        int threads, double min_impact_rate_radps);

/// comparison.json "predictability".
nlohmann::json PredictabilityJson(const Scene& scene, const ReferencePerturbationMembers& e);

/// reference/ensemble_band.csv: t,theta1_lo,theta1_hi,theta1_spread,theta1_tol[,theta2_lo,...,
/// thetaN_tol] (rad), every block of e.blocks.
std::string PerturbationBandCsv(const ReferencePerturbationMembers& e);

/// <engine>/ensemble.csv: one row per member with its perturbation and outcome, `blocks` blocks.
std::string OutcomesCsv(const std::vector<MemberOutcome>& outcomes,
                        const std::vector<MemberPerturbation>& perturbations, int blocks);
/// A cylinder's ensemble.csv: member, the amplitude factors of the three components and of the
/// initial tilt, status, overturn (time and fall azimuth), peak tilt and its time, residual and
/// RMS tilt.
std::string CylinderOutcomesCsv(const std::vector<MemberOutcome>& outcomes,
                                const std::vector<MemberPerturbation>& perturbations);
/// (A bool here was "two blocks": give the number of blocks.)
std::string OutcomesCsv(const std::vector<MemberOutcome>&, const std::vector<MemberPerturbation>&,
                        bool) = delete;

}  // namespace rockbench
