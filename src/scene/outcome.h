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
};

/// The one text form of a status, as summary.json, the CSV files and the console print it:
/// "completed", "overturned", "at_rest", "assumption_violated", "blow_up", "non_finite".
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
                                         {RunStatus::kNonFinite, "non_finite"}})

struct RunOutcome {
  RunStatus status = RunStatus::kCompleted;  ///< how the run ended
  int overturned_block = 0;                  ///< 0: none; 1 or 2: the block that overturned first
  double overturn_t_s = std::numeric_limits<double>::quiet_NaN();
  double end_t_s = 0.0;                                 ///< last simulated time, s
  double peak_theta1_rad = 0.0, peak_theta1_t_s = 0.0;  ///< largest |theta1| and when
  double peak_theta2_rad = 0.0, peak_theta2_t_s = 0.0;  ///< zero for a single block
  int impacts_ground = 0, impacts_interface = 0;
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

  int impacts() const { return impacts_ground + impacts_interface; }
  bool overturned() const { return overturned_block != 0; }
};

}  // namespace rockbench
