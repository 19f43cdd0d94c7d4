// The ground's displacement from its acceleration (motion/ground_displacement.h): the kinematic
// drive's leapfrog path and its zero-phase high-pass against closed forms, and the exact
// piecewise-linear peaks of the intensity measures.
#include "motion/ground_displacement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rockbench {
namespace {

constexpr double kPi = std::numbers::pi;

// Second difference of u divided by dt^2 at step n (u_{-1} from the velocity before step 0).
double SecondDifference(const std::vector<double>& u, double v_before, double dt, size_t n) {
  const double prev = n == 0 ? u[0] - v_before * dt : u[n - 1];
  return (u[n + 1] - 2.0 * u[n] + prev) / (dt * dt);
}

// a_n = -A w^2 sin(w n dt): the acceleration of x(t) = A sin(w t), on the grid.
std::vector<double> Harmonic(double amp_m, double w_radps, double dt_s, size_t n) {
  std::vector<double> a(n);
  for (size_t k = 0; k < n; ++k) a[k] = -amp_m * w_radps * w_radps * std::sin(w_radps * k * dt_s);
  return a;
}

TEST(StepCount, CeilingOfDurationOverStep) {
  EXPECT_EQ(StepCount(1.0, 1e-3), 1000);   // a whole number of steps takes no extra one
  EXPECT_EQ(StepCount(0.0105, 1e-3), 11);  // a part step is one step
  EXPECT_EQ(StepCount(0.0, 1e-3), 0);
  EXPECT_EQ(StepCount(20.0, 1e-4), 200000);
}

TEST(SampleGroundAcceleration, SamplesEachComponentAtTheStepStarts) {
  GroundMotion m;
  m.set_horizontal(MotionComponent::FromSamples({0.0, 1.0}, 0.01, 0.0, "ramp"));
  std::vector<double> ax, ay;
  SampleGroundAcceleration(m, 1e-3, 11, &ax, &ay);
  ASSERT_EQ(ax.size(), 11u);
  ASSERT_EQ(ay.size(), 11u);
  for (size_t n = 0; n < 11; ++n) {
    EXPECT_EQ(ax[n], m.xg_mps2(static_cast<double>(n) * 1e-3));
    EXPECT_EQ(ay[n], 0.0);
  }
}

TEST(IntegrateGroundPath, ConstantAccelerationIsTheLeapfrogParabola) {
  // From rest (u_0 = u_{-1} = 0), u_{n+1} - 2 u_n + u_{n-1} = dt^2 a gives u_n = a dt^2 n (n + 1)
  // / 2: the continuous a t^2 / 2 plus a dt t / 2 (the leapfrog's half-step start). A rounding
  // made at step k is carried into every later u with weight (n - k) (the recurrence's linear
  // mode): about n^2 eps / 12 = 1e-11 of the value at n = 1000; 2e-11 relative.
  const double a = 2.0, dt = 1e-3;
  const GroundPath p = IntegrateGroundPath(std::vector<double>(1000, a), dt, 0.0);
  ASSERT_EQ(p.u_m.size(), 1001u);
  for (size_t n = 0; n <= 1000; ++n) {
    const double exact = a * dt * dt * n * (n + 1) / 2.0;
    EXPECT_NEAR(p.u_m[n], exact, 2e-11 * exact) << n;
  }
  EXPECT_EQ(p.velocity_before_mps, 0.0);
  EXPECT_EQ(p.raw_peak_m, p.u_m.back());
}

TEST(IntegrateGroundPath, HarmonicWithoutCorrectionIsTheDiscreteClosedForm) {
  // For a_n = -A w^2 sin(w n dt) the leapfrog recurrence from rest has the exact solution
  // u_n = A' (sin(w n dt) - n sin(w dt)), A' = A (w dt)^2 / (4 sin^2(w dt / 2)): the second
  // difference of sin(w n dt) is -4 sin^2(w dt / 2) sin(w n dt), that of n is 0, and
  // u_0 = u_{-1} = 0. As dt -> 0 it is A sin(w t) - A w t, the drift of a harmonic integrated
  // from rest. Rounding carried by the recurrence's linear mode grows to about n^2 eps / 12 =
  // 1.5e-10 of the path's size (A w t ~ 1.3 m for A = 0.05 m) after 4000 steps: 1e-9 m.
  const double amp = 0.05, w = 2.0 * kPi, dt = 1e-3;
  const GroundPath p = IntegrateGroundPath(Harmonic(amp, w, dt, 4000), dt, 0.0);
  const double s = std::sin(0.5 * w * dt);
  const double amp_d = amp * (w * dt) * (w * dt) / (4.0 * s * s);
  for (size_t n = 0; n <= 4000; n += 137) {
    const double exact = amp_d * (std::sin(w * n * dt) - n * std::sin(w * dt));
    EXPECT_NEAR(p.u_m[n], exact, 1e-9) << n;
    // And the continuous path within the leapfrog's (w dt)^2 / 12 = 3.3e-6 relative (of A w t
    // <= 1.3 m): 1e-5 m.
    const double t = n * dt;
    EXPECT_NEAR(p.u_m[n], amp * (std::sin(w * t) - w * t), 1e-5) << n;
  }
}

TEST(IntegrateGroundPath, TheHighPassHalvesAHarmonicAtItsCornerAndRemovesTheDrift) {
  // The correction is the zero-phase 4th-order Butterworth high-pass |H_HP|^2 = r^4 / (1 + r^4),
  // r = tan(pi f dt) / tan(pi fc dt) (bilinear transform with pre-warping): a harmonic at the
  // corner (r = 1) keeps half its amplitude, unshifted, and at 4 x the corner r^4 / (1 + r^4).
  // The drift -A' n sin(w dt) is a straight line, which a zero-phase low-pass keeps: it goes.
  // The start-up transients (the ramp's kink at t = 0, the reflection at the end) decay as
  // exp(-0.707 2 pi fc t) = exp(-2.2 t) at fc = 0.5 Hz from at most 6 A (the ramp's slope A w
  // times 0.45 s): below 1e-10 A after 12 s. Between 12 and 28 s of a 40 s record only rounding
  // is left (the filter's poles are 1 - 2e-3 from 1 at dt = 1e-3:
  // rounding of the 6-25 m ramp grows by ~1/k^2 ~ 4e5, ~1e-9 m; measured 1.8e-9 A at the corner,
  // 8.3e-9 A at 4 x). Tolerance 1e-7 A.
  const double amp = 0.05, dt = 1e-3, fc = 0.5;
  for (const double f : {0.5, 2.0}) {
    const double w = 2.0 * kPi * f;
    const GroundPath p = IntegrateGroundPath(Harmonic(amp, w, dt, 40000), dt, fc);
    const double s = std::sin(0.5 * w * dt);
    const double amp_d = amp * (w * dt) * (w * dt) / (4.0 * s * s);
    const double r = std::tan(kPi * f * dt) / std::tan(kPi * fc * dt);
    const double gain = std::pow(r, 4) / (1.0 + std::pow(r, 4));
    if (f == fc) {
      EXPECT_NEAR(gain, 0.5, 1e-15);
    }
    for (size_t n = 12000; n <= 28000; n += 331) {
      EXPECT_NEAR(p.u_m[n], gain * amp_d * std::sin(w * n * dt), 1e-7 * amp)
          << "f " << f << ", n " << n;
    }
    // The raw peak is the drift's: A' (w t + 1) at most.
    EXPECT_GT(p.raw_peak_m, amp * w * 39.0);
  }
}

TEST(IntegrateGroundPath, WithoutCorrectionItIsTheExactDoubleIntegralOfTheSamples) {
  const double dt = 1e-3;
  std::vector<double> a(500);
  for (size_t n = 0; n < a.size(); ++n) a[n] = 3.0 * std::sin(7.0 * n * dt) + 0.5;
  const GroundPath p = IntegrateGroundPath(a, dt, 0.0);
  ASSERT_EQ(p.u_m.size(), a.size() + 1);
  EXPECT_EQ(p.u_m[0], 0.0);
  EXPECT_EQ(p.velocity_before_mps, 0.0);
  // The ground's velocity change per step is exactly what the inertial drive gives the blocks.
  for (size_t n = 0; n < a.size(); ++n) {
    EXPECT_NEAR(SecondDifference(p.u_m, p.velocity_before_mps, dt, n), a[n], 1e-9 * 3.5) << n;
  }
  EXPECT_DOUBLE_EQ(p.raw_peak_m, *std::max_element(p.u_m.begin(), p.u_m.end()));
}

TEST(IntegrateGroundPath, BaselineCorrectionRemovesDriftAndKeepsTheShaking) {
  const double dt = 1e-3, fc = 0.1;
  const size_t n = 20000;  // 20 s
  // 0.2 s of 1 m/s^2 leaves the ground drifting at 0.2 m/s: 4 m after 20 s.
  std::vector<double> pulse(n, 0.0);
  for (size_t k = 0; k < 200; ++k) pulse[k] = 1.0;
  const GroundPath p = IntegrateGroundPath(pulse, dt, fc);
  const std::vector<double>& u = p.u_m;
  const double v0 = p.velocity_before_mps;
  // 1/2 a t^2 in the pulse, then 0.2 m/s (+ the leapfrog's 1e-4 m).
  EXPECT_NEAR(p.raw_peak_m, 0.02 + 0.2 * 19.8, 2e-4);
  double peak = 0.0;
  for (double x : u) peak = std::max(peak, std::abs(x));
  // Measured: the corrected ground starts 0.103 m left (the zero-phase baseline sees the drift
  // coming), is back near 0 after 2 s and ends 1.3 mm from 0; it never goes beyond 0.108 m.
  EXPECT_LT(peak, 0.12);
  EXPECT_LT(std::abs(u.back()), 0.005);
  EXPECT_GT(std::abs(u.front()), 0.05);
  // The velocity before step 0 continues the corrected path: the ground starts moving
  // smoothly (second difference at step 0 matches its neighbours').
  EXPECT_NEAR(SecondDifference(u, v0, dt, 0) - pulse[0], SecondDifference(u, v0, dt, 1) - pulse[1],
              1e-5);

  // A 5 Hz harmonic, 2 s, 0.3 g: |H_HP(5 Hz)|^2 = 1 - 1.6e-7 leaves the shaking itself alone;
  // what changes is the burst's mean velocity A / omega = 0.094 m/s, removed by a slow ground
  // acceleration of measured 0.011 m/s^2 = 0.38% of A. Bound 0.5%.
  std::vector<double> h(n, 0.0);
  const double A = 0.3 * kStandardGravity_mps2;
  for (size_t k = 0; k < 2000; ++k) h[k] = A * std::sin(2.0 * kPi * 5.0 * k * dt);
  const GroundPath ph = IntegrateGroundPath(h, dt, fc);
  double worst = 0.0;
  for (size_t k = 0; k < n; ++k) {
    worst =
        std::max(worst, std::abs(SecondDifference(ph.u_m, ph.velocity_before_mps, dt, k) - h[k]));
  }
  EXPECT_LT(worst, 5e-3 * A);
}

TEST(IntegrateGroundPath, NoSamplesIsAGroundAtRest) {
  const GroundPath p = IntegrateGroundPath({}, 1e-3, 0.1);
  ASSERT_EQ(p.u_m.size(), 1u);
  EXPECT_EQ(p.u_m[0], 0.0);
  EXPECT_EQ(p.raw_peak_m, 0.0);
}

TEST(ExactGroundPeaks, ConstantAccelerationThenRest) {
  // a = 1 m/s^2 for 1 s: v = 1 m/s, d = 0.5 m; then 2 s at constant v: d = 2.5 m. Exact in
  // binary (sums of halves and sixths of small integers within 1e-15).
  const GroundPeaks p = ExactGroundPeaks({1.0, 1.0}, 1.0, 2.0);
  EXPECT_NEAR(p.velocity_mps, 1.0, 1e-15);
  EXPECT_NEAR(p.displacement_m, 2.5, 1e-15);
  EXPECT_NEAR(ExactGroundPeaks({1.0, 1.0}, 1.0, 0.0).displacement_m, 0.5, 1e-15);
}

TEST(ExactGroundPeaks, TriangleAndInSegmentPeaks) {
  // a: 0 -> 1 -> 0 over 2 s: v(1) = 1/2, v(2) = 1; d(1) = 1/6, d(2) = 1/6 + 5/6 = 1.
  GroundPeaks p = ExactGroundPeaks({0.0, 1.0, 0.0}, 1.0, 0.0);
  EXPECT_NEAR(p.velocity_mps, 1.0, 1e-15);
  EXPECT_NEAR(p.displacement_m, 1.0, 1e-15);
  // a = 1 - tau over 2 s: v = tau - tau^2 / 2 peaks at 1/2 inside the segment (tau = 1, where a
  // crosses 0) and is 0 at the end; d = tau^2 / 2 - tau^3 / 6 = 2/3 at the end.
  p = ExactGroundPeaks({1.0, -1.0}, 2.0, 0.0);
  EXPECT_NEAR(p.velocity_mps, 0.5, 1e-15);
  EXPECT_NEAR(p.displacement_m, 2.0 / 3.0, 1e-15);
  // a = -1 + tau over 2 s from rest, then held: d peaks at 2/3 below 0 at the end, v = 0 after.
  p = ExactGroundPeaks({-1.0, 1.0}, 2.0, 5.0);
  EXPECT_NEAR(p.displacement_m, 2.0 / 3.0, 1e-15);
}

}  // namespace
}  // namespace rockbench
