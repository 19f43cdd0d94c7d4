#pragma once
// The standard normal distribution for the fragility tests, written here from erfc (not GSL's,
// which the fits use): its CDF and the CDF's inverse.
#include <cmath>

namespace rockbench::testing_util {

/// The standard normal CDF Phi(z) = erfc(-z / sqrt 2) / 2.
inline double Phi(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

/// Phi^-1(p) by bisection on [-40, 40]: 200 halvings leave an interval far below a double's
/// spacing, so the result is Phi's inverse to rounding.
inline double PhiInverse(double p) {
  double lo = -40, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Phi(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace rockbench::testing_util
