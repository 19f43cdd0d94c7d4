#include "compare/body_quantity.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rockbench {

AngleAgreement CompareBodyQuantity(const History& engine, std::string_view stem, int body,
                                   const std::function<double(double t_s)>& reference,
                                   double tolerance_rad, double until_s) {
  if (body < 1 || body > engine.blocks) {
    throw std::invalid_argument("no body " + std::to_string(body) + " in a history of " +
                                std::to_string(engine.blocks));
  }
  AngleAgreement a;
  a.quantity = std::string(stem);
  a.tolerance_rad = a.tolerance_min_rad = a.floor_rad = tolerance_rad;
  a.horizon_s = until_s;
  a.peak_tolerance_rad = tolerance_rad;
  double sum2 = 0.0, sum2_horizon = 0.0;
  int n = 0, n_horizon = 0;
  bool crossed = false;
  for (const Sample& s : engine.samples) {
    if (s.t_s > until_s) break;
    const double value = StateValue(engine, s, stem, body);
    const double expected = reference(s.t_s);
    const double error = std::abs(value - expected);
    ++n;
    sum2 += error * error;
    if (error > a.max_abs_error_rad) a.max_abs_error_rad = error;
    const double ratio = error / tolerance_rad;
    if (ratio > a.max_error_ratio) {
      a.max_error_ratio = ratio;
      a.max_error_ratio_t_s = s.t_s;
    }
    if (!crossed && error > tolerance_rad) {
      crossed = true;
      a.within_tolerance = false;
      a.horizon_s = s.t_s;
      a.tolerance_at_horizon_rad = tolerance_rad;
    }
    if (!crossed) {
      ++n_horizon;
      sum2_horizon += error * error;
      a.max_abs_error_horizon_rad = std::max(a.max_abs_error_horizon_rad, error);
    }
    if (std::abs(expected) > a.peak_reference_rad) {
      a.peak_reference_rad = std::abs(expected);
      a.peak_reference_t_s = s.t_s;
    }
    if (std::abs(value) > a.peak_engine_rad) {
      a.peak_engine_rad = std::abs(value);
      a.peak_engine_t_s = s.t_s;
    }
  }
  a.rms_error_rad = n > 0 ? std::sqrt(sum2 / n) : 0.0;
  a.rms_error_horizon_rad = n_horizon > 0 ? std::sqrt(sum2_horizon / n_horizon) : 0.0;
  // Everything is predictable here: the reference is a given function.
  a.max_error_ratio_predictable = a.max_error_ratio;
  a.max_abs_error_predictable_rad = a.max_abs_error_rad;
  a.rms_error_predictable_rad = a.rms_error_rad;
  if (a.peak_reference_rad > 0.0) {
    a.peak_rel_error = (a.peak_engine_rad - a.peak_reference_rad) / a.peak_reference_rad;
  }
  a.peak_time_error_s = a.peak_engine_t_s - a.peak_reference_t_s;
  a.peak_within_tolerance = std::abs(a.peak_engine_rad - a.peak_reference_rad) <= tolerance_rad;
  return a;
}

}  // namespace rockbench
