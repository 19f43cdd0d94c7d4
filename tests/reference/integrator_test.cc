// The Runge-Kutta steps of integrator.h: the Dormand-Prince 8(5,3) tableau against its order
// conditions, the observed orders of its step and its dense output on a closed form, the
// ordering of the three schemes, and the reference run with it against the default pair.
#include "reference/integration/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/thesis_scene.h"
#include "reference/simulate.h"

namespace rockbench::reference {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The linearized rocking arc theta'' = p^2 (theta - theta_c), both state pairs alike: its
// solution theta_c + (theta0 - theta_c) cosh(p t) is known in closed form.
constexpr double kP2 = 3.0, kThetaC = 0.25, kTheta0 = 0.2;
Vec4 Arc(double, const Vec4& y) {
  return {y[2], y[3], kP2 * (y[0] - kThetaC), kP2 * (y[1] - kThetaC)};
}
double ArcExact(double t) {
  return kThetaC + (kTheta0 - kThetaC) * std::cosh(std::sqrt(kP2) * t);
}

enum class Scheme { kRk4, kDopri5, kDop853 };

StepResult Step(Scheme scheme, double t, const Vec4& y, const Vec4& f, double h) {
  switch (scheme) {
    case Scheme::kRk4:
      return Rk4Step(Arc, t, y, f, h);
    case Scheme::kDopri5:
      return Dopri5Step(Arc, t, y, f, h, 1.0, 1.0);
    case Scheme::kDop853:
      break;
  }
  return Dop853Step(Arc, t, y, f, h, 1.0, 1.0);
}

// |theta(T) - exact| after n equal steps of the scheme.
double ArcError(Scheme scheme, int n, double T) {
  Vec4 y{kTheta0, kTheta0, 0.0, 0.0};
  Vec4 f = Arc(0.0, y);
  const double h = T / n;
  for (int i = 0; i < n; ++i) {
    const StepResult r = Step(scheme, i * h, y, f, h);
    y = r.y1;
    f = r.f1;
  }
  return std::abs(y[0] - ArcExact(T));
}

// Row sums equal the nodes (each stage is consistent), and the weights integrate c^k exactly
// for k = 0..7 (the quadrature conditions of an 8th-order method); the error estimators are
// differences of consistent weights, so they sum to zero. Each sum has at most 16 terms of
// magnitude |a|, so rounding is below 16 eps sum |a|; 64 eps sum |a| is asked.
TEST(Dop853, TableauMeetsTheConsistencyAndQuadratureConditions) {
  using namespace dop853;
  for (int s = 1; s < 16; ++s) {
    double sum = 0.0, mag = 0.0;
    for (int j = 0; j < s; ++j) {
      sum += kA[s][j];
      mag += std::abs(kA[s][j]);
    }
    EXPECT_NEAR(sum, kC[s], 64 * kEps * mag) << "stage " << s;
  }
  for (int k = 0; k <= 7; ++k) {
    double sum = 0.0, mag = 0.0;
    for (int j = 0; j < 12; ++j) {
      sum += kA[12][j] * std::pow(kC[j], k);
      mag += std::abs(kA[12][j] * std::pow(kC[j], k));
    }
    EXPECT_NEAR(sum, 1.0 / (k + 1), 64 * kEps * mag) << "c^" << k;
  }
  double e3 = 0.0, e5 = 0.0, mag3 = 0.0, mag5 = 0.0;
  for (int j = 0; j < 12; ++j) {
    e3 += kE3[j];
    e5 += kE5[j];
    mag3 += std::abs(kE3[j]);
    mag5 += std::abs(kE5[j]);
  }
  EXPECT_NEAR(e3, 0.0, 64 * kEps * mag3);
  EXPECT_NEAR(e5, 0.0, 64 * kEps * mag5);
}

// The global error of an order-q scheme falls by 2^q when the step halves. Steps T/4 and T/8
// (p h = 0.17 and 0.087) are in the asymptotic range for dop853 and far above rounding
// (the finer error is 3e-12 against |theta| ulps of 3e-17).
TEST(Dop853, StepIsEighthOrder) {
  const double T = 0.8;
  const double e1 = ArcError(Scheme::kDop853, 4, T), e2 = ArcError(Scheme::kDop853, 8, T);
  EXPECT_NEAR(std::log2(e1 / e2), 8.0, 0.3) << e1 << " " << e2;
}

// The continuous extension is 7th order: its error inside one step is O(h^8), so halving the
// step divides the error at the step's midpoint by 2^8.
TEST(Dop853, DenseOutputIsSeventhOrder) {
  auto mid_error = [](double h) {
    const Vec4 y{kTheta0, kTheta0, 0.0, 0.0};
    const StepResult r = Dop853Step(Arc, 0.0, y, Arc(0.0, y), h, 1.0, 1.0);
    EXPECT_EQ(r.dense.At(h), r.y1);  // the interpolant ends on the step's solution
    EXPECT_EQ(r.dense.At(0.0), y);
    return std::abs(r.dense.At(0.5 * h)[0] - ArcExact(0.5 * h));
  };
  const double d1 = mid_error(0.4), d2 = mid_error(0.2);
  EXPECT_NEAR(std::log2(d1 / d2), 8.0, 0.5) << d1 << " " << d2;
}

// The more accurate scheme has the smaller error at the same step. dop853's error estimate is
// h e5^2 / sqrt(e5^2 + 0.01 e3^2) with e5 = O(h^5) and e3 = O(h^3) (its 5th- and 3rd-order
// estimators, without the factor h): for small steps the 3rd-order term dominates the
// denominator and err = O(h^8), which is why its controller scales the step by err^(-1/8).
TEST(Dop853, MoreAccurateSchemesHaveSmallerErrors) {
  const double T = 0.8;
  for (const int n : {4, 8, 16}) {
    const double rk4 = ArcError(Scheme::kRk4, n, T);
    const double dopri5 = ArcError(Scheme::kDopri5, n, T);
    const double dop853 = ArcError(Scheme::kDop853, n, T);
    EXPECT_LT(dopri5, rk4) << n << " steps";
    EXPECT_LT(dop853, dopri5) << n << " steps";
  }
  const Vec4 y{kTheta0, kTheta0, 0.0, 0.0};
  const double err1 = Dop853Step(Arc, 0.0, y, Arc(0.0, y), 0.2, 0.0, 1.0).err;
  const double err2 = Dop853Step(Arc, 0.0, y, Arc(0.0, y), 0.1, 0.0, 1.0).err;
  EXPECT_NEAR(std::log2(err1 / err2), 8.0, 0.5) << err1 << " " << err2;
}

// DenseStep::Bounds encloses each scheme's interpolant over its step (sampled at 1001 points,
// the ends included), and is not vacuous: its excess over the sampled range is the
// remainder's term, O(h^2) against the chord's O(h), so relative to the chord it falls as h:
// measured at most 1.01 h / (1 s) on this arc (p = 1.7 rad/s); 1.25 h / (1 s) is asked.
TEST(DenseStep, BoundsEncloseTheInterpolantTightly) {
  for (const Scheme scheme : {Scheme::kRk4, Scheme::kDopri5, Scheme::kDop853}) {
    for (const double h : {0.4, 0.05, 1e-6}) {
      SCOPED_TRACE("scheme " + std::to_string(static_cast<int>(scheme)) + ", h " +
                   std::to_string(h));
      const Vec4 y{kTheta0, kTheta0, 0.1, -0.1};
      const StepResult r = Step(scheme, 0.3, y, Arc(0.3, y), h);
      Vec4 lo, hi, vmin = y, vmax = y;
      r.dense.Bounds(&lo, &hi);
      for (int k = 0; k <= 1000; ++k) {
        const Vec4 v = r.dense.At(0.3 + h * k / 1000.0);
        for (int i = 0; i < 4; ++i) {
          EXPECT_LE(lo[i], v[i]) << "component " << i;
          EXPECT_GE(hi[i], v[i]) << "component " << i;
          vmin[i] = std::min(vmin[i], v[i]);
          vmax[i] = std::max(vmax[i], v[i]);
        }
      }
      for (int i = 0; i < 4; ++i) {
        const double chord = std::abs(r.y1[i] - y[i]);
        const double excess = (hi[i] - lo[i]) - (vmax[i] - vmin[i]);
        EXPECT_LE(excess, 1.25 * h * chord + 1e-12) << "component " << i;
      }
    }
  }
}

// The thesis's free-rocking stack (6 s, 37 impacts and transitions) run with dop853 and with
// the default dopri5, both at rtol 1e-12: the same events and angles that agree to 1e-9 rad.
// That bound is 30 times the largest whole-run difference between dopri5 at rtol 1e-12 and
// at 1e-13 on the benchmark scenes (3e-11 rad, docs/performance-reference.md).
TEST(Dop853, ThesisStackAgreesWithTheDefaultPair) {
  Scene sc = testing_util::ThesisFreeRockingStack();
  const Result dopri5 = Simulate(sc, GroundMotion{});
  sc.model.integrator = Integrator::kDop853;
  const Result dop853 = Simulate(sc, GroundMotion{});
  ASSERT_EQ(dop853.history.events.size(), dopri5.history.events.size());
  for (size_t i = 0; i < dopri5.history.events.size(); ++i) {
    EXPECT_EQ(dop853.history.events[i].kind, dopri5.history.events[i].kind) << i;
    EXPECT_EQ(dop853.history.events[i].mode_after, dopri5.history.events[i].mode_after) << i;
    EXPECT_NEAR(dop853.history.events[i].t_s, dopri5.history.events[i].t_s, 1e-9) << i;
  }
  EXPECT_EQ(dop853.summary.status, dopri5.summary.status);
  double max_diff = 0.0;
  for (double t = 0.0; t <= 6.0; t += 1e-3) {
    const Sample a = dopri5.trajectory.At(t), b = dop853.trajectory.At(t);
    max_diff = std::max({max_diff, std::abs(a.theta_rad[0] - b.theta_rad[0]),
                         std::abs(a.theta_rad[1] - b.theta_rad[1])});
  }
  EXPECT_LT(max_diff, 1e-9);
  // Fewer, longer steps: the reason to offer it.
  EXPECT_LT(dop853.summary.steps_accepted, dopri5.summary.steps_accepted);
}

}  // namespace
}  // namespace rockbench::reference
