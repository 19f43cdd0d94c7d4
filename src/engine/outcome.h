#pragma once
/// The outcome of one run, the same for the reference and every engine: how it ended, the peaks,
/// the impacts, and (engines) what the model forbids that the run did. The harness compares
/// these; summary.json carries them with everything else each side measured.
#include <iosfwd>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockbench {

/// How a run (the reference's or an engine's) ended.
enum class RunStatus {
  kCompleted,           ///< ran to the end of the record
  kOverturned,          ///< a block overturned
  kAtRest,              ///< came to rest after the motion ended (settled-after time)
  kAssumptionViolated,  ///< the reference: the model's assumptions stop holding
  kBlowUp,              ///< engines: the monitor flagged a blow-up
  kNonFinite,           ///< the state, energy, an event time or a force stopped being finite
  /// A block slid off its support: its base left the top face of the block below (the ground
  /// is infinite: block 1 never leaves it). Not an overturn: the block did not tip over.
  kLeftSupport,
};

/// The one text form of a status, as summary.json, the CSV files and the console print it:
/// "completed", "overturned", "at_rest", "assumption_violated", "blow_up", "non_finite",
/// "left_support".
const char* StatusText(RunStatus status);

/// The status whose StatusText is `text`; nullopt for any other text (statuses read back from
/// files).
std::optional<RunStatus> ParseRunStatus(std::string_view text);

/// Writes StatusText(status) (test failures, logs).
std::ostream& operator<<(std::ostream& os, RunStatus status);

/// JSON keeps the text form. Reading a text that is not a status gives kCompleted (the macro's
/// default): where a file may hold anything, use ParseRunStatus.
NLOHMANN_JSON_SERIALIZE_ENUM(RunStatus, {{RunStatus::kCompleted, "completed"},
                                         {RunStatus::kOverturned, "overturned"},
                                         {RunStatus::kAtRest, "at_rest"},
                                         {RunStatus::kAssumptionViolated, "assumption_violated"},
                                         {RunStatus::kBlowUp, "blow_up"},
                                         {RunStatus::kNonFinite, "non_finite"},
                                         {RunStatus::kLeftSupport, "left_support"}})

/// Every block's peak tilt and every interface's impact count: what a run's outcome
/// (RunOutcome) and the reference's own summary (reference::Summary) both tally, one entry per
/// block.
struct PeaksAndImpacts {
  /// Largest |theta_k| and when (s), one entry per block (block k at k - 1).
  std::vector<double> peak_theta_rad, peak_theta_t_s;
  /// Impacts per interface, one entry per block: [0] block 1 (or the whole stack) on the
  /// ground, [k] block k + 1 on block k.
  std::vector<int> impacts_at;

  /// No blocks (fill it, or build it for a number of blocks).
  PeaksAndImpacts() = default;
  /// `blocks` blocks: no peak, no impact.
  explicit PeaksAndImpacts(int blocks)
      : peak_theta_rad(static_cast<size_t>(blocks), 0.0),
        peak_theta_t_s(static_cast<size_t>(blocks), 0.0),
        impacts_at(static_cast<size_t>(blocks), 0) {}

  int blocks() const { return static_cast<int>(peak_theta_rad.size()); }
  /// Impacts of block 1 (or the whole stack) on the ground.
  int impacts_ground() const { return impacts_at.empty() ? 0 : impacts_at[0]; }
  /// Impacts at every interface between blocks.
  int impacts_interface() const { return impacts() - impacts_ground(); }
  int impacts() const {
    int n = 0;
    for (const int i : impacts_at) n += i;
    return n;
  }
};

/// How a run ended, its peaks and impacts (PeaksAndImpacts) and, for engines, what the model
/// forbids that the run did.
struct RunOutcome : PeaksAndImpacts {
  RunStatus status = RunStatus::kCompleted;  ///< how the run ended
  int overturned_block = 0;                  ///< 0: none; 1..N: the block that overturned first
  double overturn_t_s = std::numeric_limits<double>::quiet_NaN();
  /// 0: none; 2..N: the first block whose base left its support's top face (slid off it).
  int left_support_block = 0;
  /// When it did, s (NaN: none).
  double left_support_t_s = std::numeric_limits<double>::quiet_NaN();
  double end_t_s = 0.0;  ///< last simulated time, s
  /// Engines: the flags their monitor raised ("sliding", "uplift", "penetration",
  /// "energy_growth", "blow_up"), in that order; empty for the reference.
  std::vector<std::string> violations;
  /// When each flag of `violations` was first raised (s), in the same order.
  std::vector<double> violation_onsets_t_s;
  /// The flags raised at the scale the verdict resolves (slip, uplift or penetration above 1%
  /// of the critical angle times the width of a block; energy growth and blow-up as flagged),
  /// and when, s.
  std::vector<std::string> significant_violations;
  std::vector<double> significant_onsets_t_s;

  /// No blocks (fill it, or build it for a number of blocks).
  RunOutcome() = default;
  /// The outcome of a run of `blocks` blocks: no peak, no impact.
  explicit RunOutcome(int blocks) : PeaksAndImpacts(blocks) {}

  bool overturned() const { return overturned_block != 0; }
  bool left_support() const { return left_support_block != 0; }
};

/// The name of interface k (k = 0: block 1 on the ground; k: block k + 1 on block k) in the
/// keys of summaries: "ground"; "interface" in a stack of two blocks; "interface<k + 1>" in a
/// stack of three or more ("interface3": block 3 on block 2; docs/outputs.md).
std::string InterfaceName(int k, int blocks);

/// The interface of an impact event's kind, InterfaceName(k, blocks) + "_impact": 0 for
/// "ground_impact", 1 for "interface_impact" (two blocks), k for "interface<k + 1>_impact"
/// (three or more); -1 for any other kind (a transition, "interface1_impact", ...).
int ImpactInterface(std::string_view kind);

}  // namespace rockbench
