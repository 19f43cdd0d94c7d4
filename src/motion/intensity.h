#pragma once
/// Intensity measures of a base-motion component: the scalar summaries of a ground motion that
/// fragility studies plot against (PGA, PGV, PGD, Arias intensity, the pulse period of a pulse).
/// Velocity and displacement are the exact integrals of the component as the simulations see it
/// (piecewise linear between samples, from rest at t = 0), without baseline correction
/// (ExactGroundPeaks, motion/ground_displacement.h): a processed record (PEER's) is already
/// corrected; a raw one may drift, and its PGD says so. (The kinematic drive and the animations
/// move the ground along IntegrateGroundPath instead, the engines' step-grid path.)
#include <optional>

#include "motion/ground_motion.h"

namespace rockbench {

struct IntensityMeasures {
  double pga_mps2 = 0.0;  ///< peak |a|, m/s^2
  double pga_t_s = 0.0;   ///< its time (the first if several), s
  double pgv_mps = 0.0;   ///< peak |v|, v(t) = integral of a from 0, m/s
  double pgd_m = 0.0;     ///< peak |d|, d(t) = integral of v from 0, m
  /// Arias intensity, pi / (2 g0) integral of a^2 dt, m/s (g0 = kStandardGravity_mps2).
  double arias_mps = 0.0;
  /// Time between 5% and 95% of the Arias intensity (significant duration D5-95), s.
  double significant_duration_s = 0.0;
  /// A pulse's period: 1/f for sine, cosine and Ricker pulses (a Ricker pulse's spectrum peaks
  /// at f), the duration for a rectangular pulse; none for records, synthetic motions and
  /// harmonics.
  std::optional<double> pulse_period_s;
};

/// The measures of `component` over [0, t_end_s] (t_end_s: the run's duration; a motion that
/// ends earlier is zero after; one that lasts longer is cut there: an analytic kind exactly, a
/// record at its last sample at or before t_end_s). Analytic kinds are sampled
/// at 4000 points per period (or per pulse), whose piecewise-linear integrals differ from the
/// exact ones by about (pi / 4000)^2 / 6, 1e-7 relative. Throws std::invalid_argument for a
/// non-positive or non-finite t_end_s.
IntensityMeasures MeasureIntensity(const MotionComponent& component, double t_end_s);

/// The peak of the horizontal resultant of two components (x: [base.horizontal], y:
/// [base.transverse]; either may be absent: zero).
struct ResultantPeak {
  double pga_mps2 = 0.0;  ///< max over t of sqrt(a_x(t)^2 + a_y(t)^2), m/s^2
  double t_s = 0.0;       ///< its time (the first if several), s
};

/// The peak resultant over [0, t_end_s], on the times MeasureIntensity reads each component at
/// (a record's samples up to its last at or before t_end_s; an analytic kind's 4000 points per
/// period), each component taken at the other's times too (accel_mps2). Between two consecutive
/// times of that union both components are linear for records, so |a|^2, a sum of squares of
/// linear functions, is convex there and its maximum is at one of them: the peak of two records
/// is exact (to rounding), whatever their sample intervals. With one component it is that
/// component's PGA, MeasureIntensity's. Throws std::invalid_argument for a non-positive or
/// non-finite t_end_s.
ResultantPeak MeasureResultantPga(const std::optional<MotionComponent>& x,
                                  const std::optional<MotionComponent>& y, double t_end_s);

}  // namespace rockbench
