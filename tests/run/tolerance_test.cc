// The local tolerance (run/tolerance.h): closed forms of the rule on histories whose
// envelope is known, and the single-number tolerance at the peak.
#include "run/tolerance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "compare/agreement.h"

namespace rockbench {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Housner's block B = 1 m, H = 4 m (alpha = atan(1/4), R = sqrt(17)/2 m), 10 s at 0.01 s.
Scene Block() {
  Scene s;
  s.blocks.resize(1);
  s.blocks[0].width_m = 1.0;
  s.blocks[0].height_m = 4.0;
  s.blocks[0].mass_kg = 1000.0;
  s.run.duration_s = 10.0;
  s.run.output_interval_s = 0.01;
  s.run.gravity_mps2 = 9.81;
  return s;
}

// theta1(t) = amplitude(t) sin(2 pi f t) on the output grid.
template <class Amplitude>
History Oscillation(const Scene& s, Amplitude amplitude, double f_hz) {
  History h;
  h.blocks = 1;
  for (int k = 0; k * s.run.output_interval_s <= s.run.duration_s + 1e-9; ++k) {
    Sample x(1);
    x.t_s = k * s.run.output_interval_s;
    x.theta_rad[0] = amplitude(x.t_s) * std::sin(2.0 * M_PI * f_hz * x.t_s + 0.3);
    h.samples.push_back(x);
  }
  return h;
}

TEST(LocalTolerance, IsTenPercentOfASteadyAmplitude) {
  const Scene s = Block();
  const double alpha = std::atan(0.25);
  // 0.5 alpha at 2 Hz: the window (+-2/p, p = sqrt(3 g / 4 R) = 1.88 rad/s: +-1.06 s) holds
  // several crests, sampled every 0.01 s: the envelope is the amplitude to within the sampling
  // of a crest, 1 - cos(2 pi f dt / 2) = 2e-3 relative.
  const ToleranceProfile p = LocalTolerance(s, 1,
                                            Oscillation(
                                                s, [&](double) { return 0.5 * alpha; }, 2.0));
  EXPECT_NEAR(p.window_half_s, 2.0 / std::sqrt(3.0 * 9.81 / (4.0 * std::sqrt(17.0) / 2.0)),
              1e3 * kEps);
  for (double t : {0.0, 2.5, 5.0, 9.99}) {
    EXPECT_NEAR(p.At(t), 0.1 * 0.5 * alpha, 2e-3 * 0.05 * alpha) << t;
  }
}

TEST(LocalTolerance, FollowsADecayAndStopsAtTheFloor) {
  const Scene s = Block();
  const double alpha = std::atan(0.25);
  // Amplitude 0.5 alpha e^{-t}: at t the window's largest crest is the one nearest t - w.
  const ToleranceProfile p =
      LocalTolerance(s, 1,
                     Oscillation(
                         s, [&](double t) { return 0.5 * alpha * std::exp(-t); }, 5.0));
  const double w = p.window_half_s;
  const double floor = 0.01 * alpha;
  for (double t : {1.5, 2.0, 3.0}) {
    // The window reaches back w rounded up to the grid (0.01 s); a crest every 0.2 s: the
    // envelope lies between the amplitude at t - w - 0.01 and one crest spacing later.
    const double hi = 0.1 * 0.5 * alpha * std::exp(-(t - w - 0.01));
    const double lo = 0.1 * 0.5 * alpha * std::exp(-(t - w + 0.2));
    EXPECT_LE(p.At(t), std::max(hi, floor)) << t;
    EXPECT_GE(p.At(t), std::max(lo, floor)) << t;
  }
  // Late, the motion is below the floor: 1% of alpha.
  EXPECT_DOUBLE_EQ(p.At(9.5), 0.01 * alpha);
  EXPECT_DOUBLE_EQ(p.Min(), 0.01 * alpha);
}

TEST(LocalTolerance, IsCappedAtTheCriticalAngle) {
  const Scene s = Block();
  const double alpha = std::atan(0.25);
  // A block that overturns: theta rises to pi/2. The tolerance never exceeds 10% of alpha.
  History h;
  h.blocks = 1;
  for (int k = 0; k <= 1000; ++k) {
    Sample x(1);
    x.t_s = k * 0.01;
    x.theta_rad[0] = std::min(M_PI / 2, 0.001 * std::exp(0.8 * x.t_s));
    h.samples.push_back(x);
  }
  const ToleranceProfile p = LocalTolerance(s, 1, h);
  EXPECT_DOUBLE_EQ(p.Max(), 0.1 * alpha);
  EXPECT_DOUBLE_EQ(p.cap_rad, 0.1 * alpha);
  // AngleTolerance_rad is the same rule at the peak: capped too.
  EXPECT_DOUBLE_EQ(AngleTolerance_rad(s, 1, M_PI / 2), 0.1 * alpha);
  EXPECT_DOUBLE_EQ(AngleTolerance_rad(s, 1, 0.5 * alpha), 0.05 * alpha);
  EXPECT_DOUBLE_EQ(AngleTolerance_rad(s, 1, 0.0), 0.01 * alpha);
}

TEST(LocalTolerance, ASceneToleranceIsConstant) {
  Scene s = Block();
  s.compare.tolerance_rad = 0.004;
  const ToleranceProfile p = LocalTolerance(s, 1, History{});
  EXPECT_EQ(p.At(0.0), 0.004);
  EXPECT_EQ(p.At(123.0), 0.004);
  EXPECT_EQ(AngleTolerance_rad(s, 1, 1.0), 0.004);
}

}  // namespace
}  // namespace rockbench
