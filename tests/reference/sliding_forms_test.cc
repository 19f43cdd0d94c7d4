// The closed forms of sliding and lift-off (reference/benchmarks/sliding_forms.h), each against
// a numerical integration of its own equation of motion (issue 24's checks, before the
// reference follows friction and flight).
#include "reference/benchmarks/sliding_forms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace rockbench::benchmarks {
namespace {

constexpr double kG = 9.81;

// The sliding block under the pulse, stepped at dt with each step's constant relative
// acceleration taken exactly (u += u' dt + u'' dt^2 / 2): the only error is the step in which
// the block sticks, at most dt in time and |u''| dt^2 in slip.
struct Stepped {
  double stick_t_s = 0.0, slip_m = 0.0, peak_rate_mps = 0.0;
};
Stepped StepSlidingBlock(double a, double pulse_s, double mu, double dt) {
  Stepped out;
  double u = 0.0, v = 0.0, t = 0.0;
  const double f = mu * kG;
  bool sliding = std::abs(a) > f;
  while (sliding) {
    const double ag = t < pulse_s ? a : 0.0;
    // Friction opposes the relative rate (at the start: the base's pull).
    const double dir = v != 0.0 ? (v > 0 ? 1.0 : -1.0) : (a > 0 ? -1.0 : 1.0);
    const double acc = -ag - dir * f;
    const double h = t < pulse_s ? std::min(dt, pulse_s - t) : dt;
    const double v_next = v + acc * h;
    if (t >= pulse_s && v_next * v <= 0.0) {
      // Sticks within this step: where the rate reaches zero.
      const double tau = -v / acc;
      u += v * tau + 0.5 * acc * tau * tau;
      t += tau;
      sliding = false;
      break;
    }
    u += v * h + 0.5 * acc * h * h;
    v = v_next;
    t += h;
    if (std::abs(v) > std::abs(out.peak_rate_mps)) out.peak_rate_mps = v;
  }
  out.stick_t_s = t;
  out.slip_m = u;
  return out;
}

TEST(SlidingFormsTest, ASlidingBlockUnderAPulseSlipsAndSticksAsNewmarksBlock) {
  for (const double a : {3.0, -3.0, 6.0, 20.0}) {
    for (const double mu : {0.1, 0.25}) {
      const double pulse = 0.2;
      const SlidingPulse c = SlidingBlockUnderPulse(a, pulse, mu, kG);
      ASSERT_TRUE(c.slides) << a << " " << mu;
      const Stepped s = StepSlidingBlock(a, pulse, mu, 1e-5);
      // The stepping is exact (constant accelerations), up to the rounding of 1e5 steps.
      EXPECT_NEAR(c.stick_t_s, s.stick_t_s, 1e-10 * c.stick_t_s) << a << " " << mu;
      EXPECT_NEAR(c.slip_m, s.slip_m, 1e-9 * std::abs(c.slip_m)) << a << " " << mu;
      EXPECT_NEAR(c.peak_slip_rate_mps, s.peak_rate_mps, 1e-9 * std::abs(s.peak_rate_mps));
      // The block lags the base: a pulse to the right slips it to the left.
      EXPECT_LT(c.slip_m * a, 0.0);
    }
  }
  // Friction enough: no slip at all.
  const SlidingPulse held = SlidingBlockUnderPulse(2.0, 0.2, 0.25, kG);
  EXPECT_FALSE(held.slides);
  EXPECT_EQ(held.slip_m, 0.0);
  EXPECT_THROW(SlidingBlockUnderPulse(2.0, 0.0, 0.25, kG), std::domain_error);
  EXPECT_THROW(SlidingBlockUnderPulse(NAN, 0.2, 0.25, kG), std::domain_error);
}

// z'' = -g - yg'' = -g + g (1 + eps) sin(omega t) from z = z' = 0 at t_off, by RK4 at dt; the
// landing where z crosses zero, by the cubic through the step's ends (values and slopes).
double SteppedLanding(double eps, double omega, double t_off, double dt) {
  auto acc = [&](double t) { return -kG + kG * (1.0 + eps) * std::sin(omega * t); };
  double t = t_off, z = 0.0, v = 0.0;
  for (long i = 0; i < 100000000; ++i) {
    const double k1v = acc(t), k1z = v;
    const double k2v = acc(t + dt / 2), k2z = v + dt / 2 * k1v;
    const double k3v = acc(t + dt / 2), k3z = v + dt / 2 * k2v;
    const double k4v = acc(t + dt), k4z = v + dt * k3v;
    const double zn = z + dt / 6 * (k1z + 2 * k2z + 2 * k3z + k4z);
    const double vn = v + dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (i > 10 && zn < 0.0) {
      // Hermite cubic on [0, 1]; bisect for its root.
      double lo = 0.0, hi = 1.0;
      auto h = [&](double s) {
        const double s2 = s * s, s3 = s2 * s;
        return (2 * s3 - 3 * s2 + 1) * z + (s3 - 2 * s2 + s) * dt * v + (-2 * s3 + 3 * s2) * zn +
               (s3 - s2) * dt * vn;
      };
      for (int k = 0; k < 100; ++k) {
        const double m = 0.5 * (lo + hi);
        (h(m) > 0.0 ? lo : hi) = m;
      }
      return t + 0.5 * (lo + hi) * dt;
    }
    z = zn;
    v = vn;
    t += dt;
  }
  return NAN;
}

TEST(SlidingFormsTest, ABlockLiftsOffWhenTheBaseFallsFasterThanGravityAndLandsWhenItsFlightSays) {
  const double omega = 2.0 * M_PI * 2.0;
  for (const double eps : {0.05, 0.5, 2.0}) {
    const LiftOff c = LiftOffUnderVerticalSine(eps, omega, kG);
    // The contact force m (g + yg'') is compressive before t_off and zero at it.
    const auto force = [&](double t) { return kG - kG * (1.0 + eps) * std::sin(omega * t); };
    EXPECT_GT(force(c.off_t_s * (1 - 1e-9)), 0.0);
    EXPECT_NEAR(force(c.off_t_s), 0.0, 1e-14 * kG);
    // RK4 at dt: error of order dt^4 in z, so a landing time to about 1e-10 s at dt = 1e-5 s.
    const double t_land = SteppedLanding(eps, omega, c.off_t_s, 1e-5);
    EXPECT_NEAR(c.land_t_s, t_land, 1e-9) << eps;
    EXPECT_GT(c.land_t_s, c.off_t_s);
    EXPECT_LT(c.landing_rate_mps, 0.0);
    EXPECT_GT(c.peak_height_m, 0.0);
    EXPECT_NEAR(FlightHeight_m(c.land_t_s, eps, omega, kG), 0.0, 1e-12 * c.peak_height_m + 1e-15);
  }
  // A larger eps leaves earlier and flies higher.
  EXPECT_LT(LiftOffUnderVerticalSine(2.0, omega, kG).off_t_s,
            LiftOffUnderVerticalSine(0.5, omega, kG).off_t_s);
  EXPECT_GT(LiftOffUnderVerticalSine(2.0, omega, kG).peak_height_m,
            LiftOffUnderVerticalSine(0.5, omega, kG).peak_height_m);
  EXPECT_THROW(LiftOffUnderVerticalSine(0.0, omega, kG), std::domain_error);
}

}  // namespace
}  // namespace rockbench::benchmarks
