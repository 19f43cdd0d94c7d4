// Never a NaN result (issue 21): a base motion absurd enough to drive the model's state, energy
// or contact forces past the range of a double ends the run with status "non_finite", naming the
// quantity and the time, at its last finite state. The history, the events and the summary hold
// only what was computed before that state, all of it finite. The motions are built in code
// (MotionComponent::FromSamples): the scene reader refuses such records up front.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/spike_motion.h"
#include "common/thesis_scene.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"

namespace rockbench::reference {
namespace {

constexpr double kDt = testing_util::kSpikeDt_s;  // s, the spike record's sample interval
using testing_util::Spike;

Scene OneBlockAtRest() {
  Scene sc;
  sc.blocks = {{1.0, 4.0, 1.0, 10000.0, 2500.0}};
  sc.run.duration_s = 2.0;
  sc.run.output_interval_s = 0.01;
  return sc;
}

bool Finite(const BlockValues& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

bool Finite(const Sample& s) {
  return std::isfinite(s.t_s) && Finite(s.theta_rad) && Finite(s.omega_radps);
}

bool Finite(const Event& e) {
  return std::isfinite(e.t_s) && Finite(e.omega_before_radps) && Finite(e.omega_after_radps) &&
         std::isfinite(e.energy_before_j) && std::isfinite(e.energy_after_j);
}

// What every non-finite run must satisfy: the status, a detail naming the quantity and the time,
// the first non-finite time inside [from_s, to_s] (where the motion's absurd part is), a
// history and events that end at the last finite state and are finite, and finite summary
// figures of the computed part.
void ExpectStoppedFinite(const Result& r, double from_s, double to_s) {
  const Summary& s = r.summary;
  ASSERT_EQ(s.status, RunStatus::kNonFinite) << s.status_detail;
  EXPECT_FALSE(s.non_finite_quantity.empty());
  EXPECT_TRUE(s.non_finite_value == "NaN" || s.non_finite_value == "+inf" ||
              s.non_finite_value == "-inf")
      << s.non_finite_value;
  EXPECT_NE(s.status_detail.find(s.non_finite_quantity + " is " + s.non_finite_value + " at t = "),
            std::string::npos)
      << s.status_detail;
  EXPECT_GE(s.non_finite_t_s, from_s);
  EXPECT_LE(s.non_finite_t_s, to_s);
  // The last finite state is no later than the first non-finite value, and the run ends there.
  EXPECT_LE(s.non_finite_last_t_s, s.non_finite_t_s);
  // A step never crosses a record sample: the last finite state is within one sample interval
  // (1e-12 s: the sample times are multiples of kDt rounded to doubles).
  EXPECT_GE(s.non_finite_last_t_s, from_s - kDt - 1e-12);
  ASSERT_FALSE(r.history.samples.empty());
  EXPECT_EQ(r.history.samples.back().t_s, s.non_finite_last_t_s);
  EXPECT_EQ(r.trajectory.end_s(), s.non_finite_last_t_s);
  for (const Sample& smp : r.history.samples) {
    EXPECT_TRUE(Finite(smp)) << "sample at t = " << smp.t_s;
    EXPECT_LE(smp.t_s, s.non_finite_last_t_s);
  }
  ASSERT_FALSE(r.history.events.empty());
  for (const Event& e : r.history.events) EXPECT_TRUE(Finite(e)) << e.kind << " at " << e.t_s;
  const Event& last = r.history.events.back();
  EXPECT_EQ(last.kind, "non_finite");
  EXPECT_EQ(last.t_s, s.non_finite_last_t_s);
  EXPECT_EQ(last.note, s.status_detail);
  for (const auto* values : {&s.peak_theta_rad, &s.peak_theta_t_s, &s.friction_required}) {
    for (const double v : *values) EXPECT_TRUE(std::isfinite(v));
  }
  for (const double t : s.peak_theta_t_s) EXPECT_LE(t, s.non_finite_last_t_s);
  // The minimum normal forces are finite, or +inf when no force was evaluated (null in JSON).
  for (const double v : s.min_normal_n) {
    EXPECT_FALSE(std::isnan(v) || v == -std::numeric_limits<double>::infinity());
  }
}

// One model setting per integrator and event scheme: each has its own step loop.
struct Variant {
  const char* name;
  Integrator integrator;
  EventScheme events;
};

class NonFiniteTest : public ::testing::TestWithParam<Variant> {
 protected:
  Scene WithModel(Scene sc) const {
    sc.model.integrator = GetParam().integrator;
    sc.model.events = GetParam().events;
    sc.model.step_s = 1e-3;
    return sc;
  }
};

// The stack at rest under 1e300 g: the rest criterion's corner forces overflow at the spike.
// The record is zero until 0.09 s, so nothing is computed non-finite before that; the spike's
// sample is at 0.10 s.
TEST_P(NonFiniteTest, StackAtRestUnderAnAbsurdSpike) {
  Scene sc = WithModel(testing_util::ThesisFreeRockingStack(2.0, 0.01));
  sc.initial = {};
  const Result r = Simulate(sc, Spike(1e300, 10));
  ExpectStoppedFinite(r, 0.09, 0.10);
}

// The free-rocking stack, rocking when a 1e200 g spike arrives at 1.5 s (sample 150, ramp from
// 1.49 s): the mode's accelerations overflow within the ramp. Before 1.49 s the run is the same
// run, sample for sample, as with a record of zeros: the history up to the last finite state
// is kept and the peaks are those of that part.
TEST_P(NonFiniteTest, RockingStackUnderAnAbsurdSpike) {
  const Scene sc = WithModel(testing_util::ThesisFreeRockingStack(2.0, 0.01));
  const Result r = Simulate(sc, Spike(1e200, 150));
  ExpectStoppedFinite(r, 1.49, 1.50);
  const Result zero = Simulate(sc, Spike(0.0, 150));
  ASSERT_EQ(zero.summary.status, RunStatus::kCompleted);
  size_t compared = 0;
  for (const Sample& s : r.history.samples) {
    if (s.t_s > 1.49) break;
    const Sample z = zero.trajectory.At(s.t_s);
    EXPECT_EQ(s.theta_rad[0], z.theta_rad[0]) << s.t_s;
    EXPECT_EQ(s.theta_rad[1], z.theta_rad[1]) << s.t_s;
    ++compared;
  }
  EXPECT_GE(compared, 150u);
  // The zero run's peak |theta2| (at 1.2 s in the default model) is before the spike: the
  // computed part has the same peak.
  if (zero.summary.peak_theta_t_s[1] < 1.49) {
    EXPECT_EQ(r.summary.peak_theta_rad[1], zero.summary.peak_theta_rad[1]);
    EXPECT_EQ(r.summary.peak_theta_t_s[1], zero.summary.peak_theta_t_s[1]);
  }
}

// Housner's block released from rest under the same kinds of spike.
TEST_P(NonFiniteTest, OneBlockUnderAnAbsurdSpike) {
  const Scene sc = WithModel(OneBlockAtRest());
  ExpectStoppedFinite(Simulate(sc, Spike(1e300, 50)), 0.49, 0.50);
}

// At rest the model evaluates only the corner forces: a spike near the largest double makes
// them overflow at its sample time (0.10 s), before anything moves.
TEST(NonFiniteAtRest, CornerForcesOverflowAtTheSpike) {
  Scene sc = testing_util::ThesisFreeRockingStack(2.0, 0.01);
  sc.initial = {};
  const Result r = Simulate(sc, Spike(1e307, 10));
  ExpectStoppedFinite(r, 0.10, 0.10);
  EXPECT_EQ(r.summary.non_finite_quantity, "normal force at rest");
  EXPECT_EQ(r.summary.non_finite_last_t_s, 0.09);
  EXPECT_EQ(r.summary.initiations, 0);
}

// A record whose first sample is absurd: no mode can be chosen at t = 0 because every
// candidate's contact forces are NaN. That is the non-finite status at t = 0, not an uplift.
TEST(NonFiniteAtRest, AbsurdFirstSampleStopsAtTimeZero) {
  Scene sc = testing_util::ThesisFreeRockingStack(2.0, 0.01);
  sc.initial = {};
  const Result r = Simulate(sc, Spike(1e300, 0));
  ExpectStoppedFinite(r, 0.0, 0.0);
  EXPECT_EQ(r.summary.non_finite_quantity, "contact force");
  ASSERT_EQ(r.history.samples.size(), 1u);
  EXPECT_EQ(r.history.samples[0].theta_rad[0], 0.0);
}

// The issue's finding: one 1e20 g sample, at the witness's settings (dop853 at rtol 1e-14),
// gave status completed with NaN in nearly every history row. dop853 accepts a first step of
// 8.8e-4 s whose end state is NaN (its error estimate is NaN too): the run now ends there.
TEST(NonFiniteIssue21, OneAbsurdSampleAtTheWitnessSettings) {
  Scene sc = testing_util::ThesisFreeRockingStack(2.0, 0.01);
  sc.initial = {};
  sc.model.integrator = Integrator::kDop853;
  sc.model.rtol = 1e-14;
  sc.model.atol = 1e-16;
  const Result r = Simulate(sc, Spike(1e20, 10));
  ExpectStoppedFinite(r, 0.09, 0.10);
  EXPECT_NE(r.summary.status, RunStatus::kCompleted);
}

INSTANTIATE_TEST_SUITE_P(
    Integrators, NonFiniteTest,
    ::testing::Values(Variant{"dopri5", Integrator::kDopri5, EventScheme::kLocated},
                      Variant{"dop853", Integrator::kDop853, EventScheme::kLocated},
                      Variant{"rk4", Integrator::kRk4, EventScheme::kLocated},
                      Variant{"thesis_events", Integrator::kRk4, EventScheme::kThesis}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace rockbench::reference
