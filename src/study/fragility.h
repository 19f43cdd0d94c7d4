#pragma once
/// Fragility curves: the probability that a block overturns given an intensity measure of the
/// ground motion (PGA, PGV, ...), fitted to an ensemble's outcomes as the field does (Baker 2015,
/// Earthquake Spectra 31(1), "Efficient analytical fragility function fitting using dynamic
/// structural analysis"): the lognormal form
///   P(failure | IM = x) = Phi(ln(x / median) / beta),
/// with the median and beta that maximise the binomial likelihood of the observed failures,
/// and a percentile bootstrap of the members for their confidence intervals. The optimiser is
/// GSL's (BFGS over ln median and ln beta); the normal tails are GSL's stable log-erfc and hazard
/// functions.
#include <cstdint>
#include <limits>
#include <span>
#include <string>

namespace rockbench::stats {

/// One member: its intensity measure (> 0, finite) and whether it failed (overturned).
struct FragilityPoint {
  double im = 0.0;
  bool failed = false;
};

/// A fitted lognormal fragility function.
struct LognormalFragility {
  /// False when the data admit no finite fit (reason says why: no failure, no survival, or
  /// failures and survivals perfectly separated by the IM, where beta -> 0).
  bool available = false;
  std::string reason;
  double median = std::numeric_limits<double>::quiet_NaN();  ///< IM of 50% failure (IM units)
  double beta = std::numeric_limits<double>::quiet_NaN();    ///< log-standard deviation
  double log_likelihood = std::numeric_limits<double>::quiet_NaN();
  int n = 0, failures = 0;
  /// The percentile bootstrap: resamples drawn, those without a finite fit (left out), and the
  /// central `level` intervals of the median and beta.
  int bootstrap = 0, bootstrap_degenerate = 0;
  double level = 0.95;
  double median_lo = std::numeric_limits<double>::quiet_NaN();
  double median_hi = std::numeric_limits<double>::quiet_NaN();
  double beta_lo = std::numeric_limits<double>::quiet_NaN();
  double beta_hi = std::numeric_limits<double>::quiet_NaN();
};

/// P(failure | IM = im) of a fit (NaN when it is not available).
double FragilityAt(const LognormalFragility& fit, double im);

/// Fits the lognormal fragility function by maximum likelihood, then draws `bootstrap` resamples
/// of the points (0: none) with a std::mt19937_64 seeded with `seed` (indices by UniformBelow,
/// statistics.h), refits each and keeps the central `level` percentile intervals. The same
/// input gives the same bytes. Throws std::invalid_argument for an IM that is not positive and
/// finite, or a level outside (0, 1).
LognormalFragility FitLognormalFragility(std::span<const FragilityPoint> points,
                                         int bootstrap = 1000,
                                         std::uint64_t seed = 0x726f636b62656e63,
                                         double level = 0.95);

}  // namespace rockbench::stats
