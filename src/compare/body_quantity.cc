#include "compare/body_quantity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "compare/angle_error.h"

namespace rockbench {

AngleAgreement CompareBodyQuantity(const History& engine, std::string_view stem, int body,
                                   const std::function<double(double t_s)>& reference,
                                   double tolerance_rad, double until_s) {
  if (body < 1 || body > engine.blocks) {
    throw std::invalid_argument("no body " + std::to_string(body) + " in a history of " +
                                std::to_string(engine.blocks));
  }
  const StateQuantityReader value_of(engine, stem);
  AngleAgreement a;
  a.quantity = std::string(stem);
  a.tolerance_rad = a.tolerance_min_rad = a.floor_rad = tolerance_rad;
  a.horizon_s = until_s;
  a.peak_tolerance_rad = tolerance_rad;
  // Everything is predictable here: the reference is a given function.
  AngleErrorSums sums(std::numeric_limits<double>::infinity());
  for (const Sample& s : engine.samples) {
    if (s.t_s > until_s) break;
    const double value = value_of(s, body);
    const double expected = reference(s.t_s);
    sums.Add(s.t_s, std::abs(value - expected), tolerance_rad, &a);
    if (std::abs(expected) > a.peak_reference_rad) {
      a.peak_reference_rad = std::abs(expected);
      a.peak_reference_t_s = s.t_s;
    }
    if (std::abs(value) > a.peak_engine_rad) {
      a.peak_engine_rad = std::abs(value);
      a.peak_engine_t_s = s.t_s;
    }
  }
  sums.Finish(&a);
  if (a.peak_reference_rad > 0.0) {
    a.peak_rel_error = (a.peak_engine_rad - a.peak_reference_rad) / a.peak_reference_rad;
  }
  a.peak_time_error_s = a.peak_engine_t_s - a.peak_reference_t_s;
  a.peak_within_tolerance = std::abs(a.peak_engine_rad - a.peak_reference_rad) <= tolerance_rad;
  return a;
}

}  // namespace rockbench
