#pragma once
/// Closed forms of a rigid block that slides or lifts off its base, the checks issue 24 names
/// for the reference's friction and flight (beside closed_forms.h, and as independent of
/// reference/). tests/reference/sliding_forms_test.cc checks each against a numerical
/// integration of its own equation of motion.
///
/// Conventions: base accelerations are the ground's (x positive to the right, y up), m/s^2;
/// slips are the block's base centre relative to its support, m, positive to the right (issue
/// 24's u); heights are the block's base above its support, m (issue 24's z, 0 in contact).
/// Every function throws std::domain_error outside its validity (stated in its comment).
namespace rockbench::benchmarks {

/// A block that can only slide (it never rocks: its B/H exceeds mu, or it is held upright),
/// at rest on a rigid base whose horizontal acceleration is a rectangular pulse of amplitude
/// a_mps2 (either sign) from t = 0 to pulse_s, then zero: Newmark's (1965) rigid-plastic
/// sliding block with Coulomb friction mu. It slides when |a| > mu g, with relative
/// acceleration -a + mu g sign(a) during the pulse and mu g sign(a) after it, until the
/// relative rate is zero again.
struct SlidingPulse {
  bool slides = false;
  double stick_t_s = 0.0;           ///< when it sticks again: |a| T / (mu g) (0: never slid)
  double slip_m = 0.0;              ///< the final slip: -sign(a) (|a| - mu g) |a| T^2 / (2 mu g)
  double peak_slip_rate_mps = 0.0;  ///< at the pulse's end: -sign(a) (|a| - mu g) T
};
/// Throws for pulse_s <= 0, mu <= 0, g <= 0 or a value that is not finite.
SlidingPulse SlidingBlockUnderPulse(double a_mps2, double pulse_s, double mu, double g_mps2);

/// A block resting on a rigid base whose vertical acceleration is -g (1 + eps) sin(omega t)
/// from t = 0 (eps > 0): the contact force m (g + yg'') turns tensile, and the block leaves
/// the base, at the first instant the base accelerates downward faster than gravity,
/// sin(omega t_off) = 1 / (1 + eps). It then flies: z'' = -g - yg'' with z = z' = 0 at t_off,
///   z(t) = -g s^2 / 2 - g (1 + eps) [(sin(omega t) - sin(omega t_off)) / omega^2
///          - cos(omega t_off) s / omega],   s = t - t_off,
/// and lands at the first root of z after t_off (Brent's method on GSL, bracketed by a scan of
/// a hundredth of a period), with the relative rate z'(t_land) < 0.
struct LiftOff {
  double off_t_s = 0.0;           ///< asin(1 / (1 + eps)) / omega
  double land_t_s = 0.0;          ///< the first root of z after off_t_s
  double peak_height_m = 0.0;     ///< the largest z in flight (at a root of z')
  double landing_rate_mps = 0.0;  ///< z'(land_t_s), negative
};
/// Throws for eps <= 0, omega <= 0, g <= 0 or a value that is not finite.
LiftOff LiftOffUnderVerticalSine(double eps, double omega_radps, double g_mps2);
/// z(t) of LiftOffUnderVerticalSine's flight (t >= off_t_s), m.
double FlightHeight_m(double t_s, double eps, double omega_radps, double g_mps2);

}  // namespace rockbench::benchmarks
