// Intensity measures against closed forms: a sine pulse (PGV 2A/w, PGD 2 pi A / w^2, Arias
// pi A^2 T / (4 g0)), a rectangular pulse (exact for piecewise-constant acceleration), a
// triangle record integrated by hand, an endless harmonic cut at the run's end, and a synthetic
// record's peak.
#include "motion/intensity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "motion/ground_motion.h"
#include "scene/scene.h"
#include "tests/common/analytic_motion.h"

namespace rockbench {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG0 = kStandardGravity_mps2;

MotionComponent Analytic(MotionKind kind, double amplitude_g, double f_hz, double t0_s,
                         double duration_s) {
  return MotionComponent::FromDef(
      testing_util::AnalyticMotion(kind, amplitude_g, f_hz, t0_s, duration_s));
}

// The time at which the fraction q of a sine pulse's Arias intensity is reached, by bisection on
// the closed form E(tau) = tau / 2 - sin(2 w tau) / (4 w) over E(T) = T / 2.
double SinePulseAriasTime(double q, double f) {
  const double w = 2 * kPi * f, T = 1 / f;
  double lo = 0, hi = T;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mid / 2 - std::sin(2 * w * mid) / (4 * w) < q * T / 2 ? lo : hi) = mid;
  }
  return lo;
}

TEST(Intensity, SinePulseMatchesItsClosedForms) {
  // The sampled integrals differ from the exact ones by O((pi / 4000)^2), about 1e-7 relative.
  const double A_g = 0.5, f = 1.5, t0 = 0.4, A = A_g * kG0, w = 2 * kPi * f;
  const IntensityMeasures im =
      MeasureIntensity(Analytic(MotionKind::kSinePulse, A_g, f, t0, 0.0), 5.0);
  EXPECT_NEAR(im.pga_mps2, A, 1e-6 * A);
  EXPECT_NEAR(im.pga_t_s, t0 + 0.25 / f, 1e-3 / f);
  EXPECT_NEAR(im.pgv_mps, 2 * A / w, 1e-6 * 2 * A / w);
  EXPECT_NEAR(im.pgd_m, 2 * kPi * A / (w * w), 1e-6 * 2 * kPi * A / (w * w));
  const double arias = kPi * A * A / (f * 4 * kG0);
  EXPECT_NEAR(im.arias_mps, arias, 1e-6 * arias);
  // D5-95 to within one sample (1/(4000 f)).
  EXPECT_NEAR(im.significant_duration_s, SinePulseAriasTime(0.95, f) - SinePulseAriasTime(0.05, f),
              1.0 / (4000 * f));
  ASSERT_TRUE(im.pulse_period_s.has_value());
  EXPECT_DOUBLE_EQ(*im.pulse_period_s, 1 / f);
}

TEST(Intensity, RectangularPulseIsExact) {
  // Constant A on [t0, t0 + L]: v = A L after it, d grows linearly to the run's end.
  const double A_g = 0.2, t0 = 1.0, L = 0.5, t_end = 4.0, A = A_g * kG0;
  const IntensityMeasures im =
      MeasureIntensity(Analytic(MotionKind::kRectangularPulse, A_g, 0.0, t0, L), t_end);
  EXPECT_NEAR(im.pga_mps2, A, 1e-12);
  EXPECT_NEAR(im.pgv_mps, A * L, 1e-12);
  EXPECT_NEAR(im.pgd_m, A * L * L / 2 + A * L * (t_end - t0 - L), 1e-11);
  EXPECT_NEAR(im.arias_mps, kPi / (2 * kG0) * A * A * L, 1e-12);
  EXPECT_NEAR(im.significant_duration_s, 0.9 * L, 1e-12);
  EXPECT_DOUBLE_EQ(*im.pulse_period_s, L);
}

TEST(Intensity, TriangleRecordIntegratedByHand) {
  // a = 0, 1, 0, -1, 0 m/s^2 at 1 s: v = 0.5, 1, 0.5, 0 and d = 1/6, 1, 11/6, 2 at t = 1..4;
  // after the record a = 0 and v = 0, so d stays 2 to the run's end.
  const MotionComponent c = MotionComponent::FromSamples({0, 1, 0, -1, 0}, 1.0, 0.0, "triangle");
  const IntensityMeasures im = MeasureIntensity(c, 10.0);
  EXPECT_DOUBLE_EQ(im.pga_mps2, 1.0);
  EXPECT_DOUBLE_EQ(im.pga_t_s, 1.0);
  EXPECT_NEAR(im.pgv_mps, 1.0, 1e-15);
  EXPECT_NEAR(im.pgd_m, 2.0, 1e-15);
  EXPECT_NEAR(im.arias_mps, kPi / (2 * kG0) * 4.0 / 3.0, 1e-15);
  EXPECT_FALSE(im.pulse_period_s.has_value());
  // Cut at 2 s: the first two segments only.
  const IntensityMeasures cut = MeasureIntensity(c, 2.0);
  EXPECT_NEAR(cut.pgv_mps, 1.0, 1e-15);
  EXPECT_NEAR(cut.pgd_m, 1.0, 1e-15);
  EXPECT_NEAR(cut.arias_mps, kPi / (2 * kG0) * 2.0 / 3.0, 1e-15);
}

TEST(Intensity, EndlessHarmonicIsCutAtTheRunsEnd) {
  // A sin(w t) over whole periods: PGV 2A/w, Arias pi A^2 t_end / (4 g0).
  const double A_g = 0.1, f = 2.0, t_end = 3.0, A = A_g * kG0, w = 2 * kPi * f;
  const IntensityMeasures im = MeasureIntensity(
      Analytic(MotionKind::kHarmonic, A_g, f, 0.0, std::numeric_limits<double>::infinity()), t_end);
  EXPECT_NEAR(im.pgv_mps, 2 * A / w, 1e-6 * 2 * A / w);
  EXPECT_NEAR(im.arias_mps, kPi * A * A * t_end / (4 * kG0),
              1e-6 * kPi * A * A * t_end / (4 * kG0));
  EXPECT_FALSE(im.pulse_period_s.has_value());
  EXPECT_THROW(MeasureIntensity(Analytic(MotionKind::kHarmonic, A_g, f, 0.0, 1.0), 0.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace rockbench
