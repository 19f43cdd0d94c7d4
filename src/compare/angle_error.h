#pragma once
/// One compared angle's pointwise errors, summed into its AngleAgreement: the largest and RMS
/// errors over the compared run, before its horizon, before and beyond the predictability
/// horizon, and the largest ratio to the local tolerance. Used by the comparison with the
/// reference model (agreement.h) and by any body kind's comparison (body_quantity.h).
#include "compare/agreement.h"

namespace rockbench {

class AngleErrorSums {
 public:
  /// Errors at times after `predictability_horizon_s` (s) count as beyond it; +infinity when
  /// every time is predictable.
  explicit AngleErrorSums(double predictability_horizon_s)
      : predictability_horizon_s_(predictability_horizon_s) {}

  /// Accounts a sample's error `error_rad` (>= 0) at t_s, whose local tolerance is
  /// `tolerance_rad`, to `g`: its largest errors and ratios, and its horizon, the first time
  /// the error exceeds the tolerance. Samples come in time order.
  void Add(double t_s, double error_rad, double tolerance_rad, AngleAgreement* g);

  /// Sets g's RMS errors from the samples added.
  void Finish(AngleAgreement* g) const;

 private:
  double predictability_horizon_s_;
  double all_ = 0.0, horizon_ = 0.0, predictable_ = 0.0, beyond_ = 0.0;
  int n_ = 0, n_horizon_ = 0, n_predictable_ = 0;
};

}  // namespace rockbench
