#pragma once
/// The outcome of one run, the same for the reference and every engine: how it ended, the peaks,
/// the impacts, and (engines) what the model forbids that the run did. The harness compares
/// these; summary.json carries them with everything else each side measured.
#include <limits>
#include <string>
#include <vector>

namespace rockbench {

struct RunOutcome {
  /// completed | overturned | at_rest | assumption_violated (reference) | blow_up (engines)
  std::string status;
  int overturned_block = 0;  ///< 0: none; 1 or 2: the block that overturned first
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
