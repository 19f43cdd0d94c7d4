#pragma once
/// The two-parameter fragility of rocking (Purvance, Anooshehpoor & Brune 2008, BSSA 98(6):
/// overturning against PGA and PGV/PGA): the lognormal fragility over PGA whose median depends
/// on the ratio r = PGV/PGA as a power law,
///   P(overturn | PGA, r) = Phi((ln PGA - m0 - m1 ln(r / r_ref)) / beta),
/// fitted by maximum likelihood (GSL's BFGS over m0, m1 and ln beta, as the one-parameter fit
/// in fragility.h). Its contours in the (r, PGA) plane are straight lines in log-log axes:
/// PGA_p(r) = exp(m0 + beta Phi^-1(p)) (r / r_ref)^m1.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace rockbench::stats {

/// One member: PGA (any unit, > 0), PGV/PGA (s, > 0) and whether it overturned.
struct SurfacePoint {
  double pga = 0.0;
  double ratio_s = 0.0;
  bool failed = false;
};

struct FragilitySurface {
  bool available = false;
  std::string reason;        ///< why not available (no failure, no survival, no maximum)
  double ratio_ref_s = 0.1;  ///< r_ref: the ratio at which exp(m0) is the median PGA
  double m0 = std::numeric_limits<double>::quiet_NaN();    ///< ln of the median PGA at r_ref
  double m1 = std::numeric_limits<double>::quiet_NaN();    ///< d ln(median) / d ln(r)
  double beta = std::numeric_limits<double>::quiet_NaN();  ///< log-standard deviation
  double log_likelihood = std::numeric_limits<double>::quiet_NaN();
  int n = 0, failures = 0;
  /// The PGA at which the probability of overturning is p, at ratio r (s).
  double PgaAt(double p, double ratio_s) const;
};

/// Fits the surface; `ratio_ref_s` is where m0 is read (choose a ratio inside the data).
/// Throws std::invalid_argument for a PGA or ratio that is not positive and finite.
FragilitySurface FitFragilitySurface(std::span<const SurfacePoint> points,
                                     double ratio_ref_s = 0.1);

/// How an engine's surface compares with the reference's on the same members: the ratio of
/// their median overturning PGAs, PGA_50,engine(r) / PGA_50,reference(r), at each asked ratio r,
/// with a paired percentile bootstrap (members drawn with replacement, the same draw for both
/// runs, both refitted). A ratio whose interval excludes 1 is a detected difference.
struct SurfaceMedianRatio {
  bool available = false;
  std::string reason;                 ///< why not available
  std::vector<double> ratio_s;        ///< the PGV/PGA ratios asked for (s)
  std::vector<double> estimate;       ///< the ratio of medians of the two full fits
  std::vector<double> lo, hi;         ///< the central `level` percentile interval
  int resamples = 0, degenerate = 0;  ///< drawn, and left out (a side without a finite fit)
};

/// `reference` and `engine` are the same members in the same order (point i of each is member
/// i's run). Throws std::invalid_argument for different lengths, a level outside (0, 1) or a
/// ratio that is not positive and finite. Deterministic: the draw is a std::mt19937_64 seeded
/// with `seed`, indices by UniformBelow (statistics.h).
SurfaceMedianRatio PairedSurfaceRatio(std::span<const SurfacePoint> reference,
                                      std::span<const SurfacePoint> engine,
                                      std::span<const double> at_ratio_s, int bootstrap = 400,
                                      std::uint64_t seed = 0x737572666163650a, double level = 0.95,
                                      double ratio_ref_s = 0.1);

}  // namespace rockbench::stats
