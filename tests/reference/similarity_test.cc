// Similarity: rigid rocking has no length scale of its own. A scene scaled by k in every length
// (widths, heights, depth; density unchanged), under the same base accelerations on a time axis
// scaled by sqrt(k), has the same angles at the times scaled by sqrt(k): theta_k(sqrt(k) tau) =
// theta_1(tau), every event (impacts, transitions, settling by the rest rule, initiations) at
// sqrt(k) times the time, the rates divided by sqrt(k). The model must keep that: its rest rule
// is a rate relative to sqrt(g / R), and its step bounds, event widths and rest scans are
// multiples of sqrt(R / g) or of the motion's period.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "reference/simulate.h"
#include "reference/thesis/geometry.h"
#include "tests/common/initial_state.h"

namespace rockbench::reference {
namespace {

// The thesis's stack (section 6.3), every length times k, converged tolerances.
Scene ThesisStack(double k) {
  Scene sc;
  sc.blocks = {{1.25 * k, 1.25 * k, k, 2500.0 * 1.25 * 1.25 * k * k * k, 2500.0}};
  sc.blocks.resize(1);
  sc.blocks.push_back(BlockDef{1.0 * k, 2.5 * k, k, 2500.0 * 1.0 * 2.5 * k * k * k, 2500.0});
  sc.model.rtol = 1e-12;
  sc.model.atol = 1e-14;
  return sc;
}

struct ScaledRun {
  double sqrt_k = 1.0;
  Result result;
};

// theta1, theta2 of run `r` at dimensionless time tau (the k = 1 run's seconds).
std::pair<double, double> AnglesAt(const ScaledRun& r, double tau) {
  const Sample s = r.result.trajectory.At(tau * r.sqrt_k);
  return {s.theta_rad[0], s.theta_rad[1]};
}

std::vector<Event> Events(const ScaledRun& r) {
  return r.result.history.events;
}

// The comparison of a scaled run with the k = 1 run: largest angle difference over the run on
// a grid of dimensionless times, and the events one by one.
void ExpectSimilar(const ScaledRun& base, const ScaledRun& scaled, double duration_tau,
                   const std::string& what) {
  SCOPED_TRACE(what);
  const Summary& a = base.result.summary;
  const Summary& b = scaled.result.summary;
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.impacts_ground(), b.impacts_ground());
  EXPECT_EQ(a.impacts_interface(), b.impacts_interface());
  EXPECT_EQ(a.transitions, b.transitions);
  EXPECT_EQ(a.initiations, b.initiations);
  // Angles: 1e-6 rad (the bound). Both runs are converged to rtol 1e-12; what differs
  // is rounding (sqrt(0.01) is not a binary fraction), amplified by the run's sensitivity.
  double worst = 0.0, worst_tau = 0.0;
  const int n = 20000;
  for (int i = 0; i <= n; ++i) {
    const double tau = duration_tau * i / n;
    const auto [p1, p2] = AnglesAt(base, tau);
    const auto [q1, q2] = AnglesAt(scaled, tau);
    const double d = std::max(std::abs(p1 - q1), std::abs(p2 - q2));
    if (d > worst) {
      worst = d;
      worst_tau = tau;
    }
  }
  EXPECT_LT(worst, 1e-6) << "at tau = " << worst_tau << " s";
  std::printf("[ similarity ] %s: max |dtheta| = %.3g rad at tau = %.4f s, %zu events\n",
              what.c_str(), worst, worst_tau, base.result.history.events.size());
  // Events: the same sequence, kinds, modes, dimensionless times and rates.
  const std::vector<Event> ea = Events(base), eb = Events(scaled);
  ASSERT_EQ(ea.size(), eb.size());
  double worst_dt = 0.0;
  const Geometry geo = MakeGeometry(ThesisStack(1.0));
  const double rate_tol = 1e-6 * std::sqrt(geo.g / geo.R);
  for (size_t i = 0; i < ea.size(); ++i) {
    SCOPED_TRACE("event " + std::to_string(i) + " at " + std::to_string(ea[i].t_s) + " s");
    EXPECT_EQ(ea[i].kind, eb[i].kind);
    EXPECT_EQ(ea[i].mode_before, eb[i].mode_before);
    EXPECT_EQ(ea[i].mode_after, eb[i].mode_after);
    EXPECT_EQ(ea[i].note, eb[i].note);
    worst_dt = std::max(worst_dt, std::abs(ea[i].t_s - eb[i].t_s / scaled.sqrt_k));
    // Dimensionless rates: omega sqrt(k) (rad/s of the k = 1 run), to the angle bound times
    // the rocking rate scale sqrt(g / R) (2.3 rad/s): 2.3e-6 rad/s. Measured: below 1e-11.
    EXPECT_NEAR(ea[i].omega_after_radps[0], eb[i].omega_after_radps[0] * scaled.sqrt_k, rate_tol);
    EXPECT_NEAR(ea[i].omega_after_radps[1], eb[i].omega_after_radps[1] * scaled.sqrt_k, rate_tol);
  }
  // Event times: within 1e-7 s of the k = 1 run. The angle bound above, divided by the typical
  // impact rate (~1e-2 to 1 rad/s), gives 1e-6 to 1e-4 s; the times agree far better.
  EXPECT_LT(worst_dt, 1e-7);
  std::printf("[ similarity ] %s: max |dt_event| = %.3g s (dimensionless, k = 1 seconds)\n",
              what.c_str(), worst_dt);
}

// The thesis's stack under Rinaldi Receiving Sta 228 (Northridge 1994) at 0.7 of its
// amplitude, so that nothing overturns: hundreds of impacts, block 1 settling by the rest rule
// many times while block 2 rocks, then the stack at rest after the record. The scaled runs get
// the same samples (m/s^2) at dt sqrt(k).
TEST(SimilarityTest, RecordedMotionRestAndImpactsScaleWithSqrtK) {
  Scene one = ThesisStack(1.0);
  MotionDef rec;
  rec.key = "base.horizontal";
  rec.kind = MotionKind::kFile;
  rec.file =
      std::string(ROCKBENCH_SOURCE_DIR) + "/records/northridge1994_rinaldi_receiving_sta_228.AT2";
  rec.file_as_written = rec.file.string();
  rec.scale = 0.7;
  const MotionComponent base_motion = MotionComponent::FromDef(rec);
  const double duration = 20.0;  // the record lasts 19.9 s
  std::vector<ScaledRun> runs;
  for (const double k : {1.0, 0.01, 100.0}) {
    Scene sc = ThesisStack(k);
    const double sk = std::sqrt(k);
    sc.run.duration_s = duration * sk;
    sc.run.output_interval_s = 0.01 * sk;
    GroundMotion gm;
    gm.set_horizontal(MotionComponent::FromSamples(
        base_motion.samples_mps2(), base_motion.dt_s() * sk, base_motion.t0_s() * sk, "scaled"));
    runs.push_back({sk, Simulate(sc, gm)});
  }
  const Summary& s = runs[0].result.summary;
  // The case does what it is here for: many impacts, settling and final rest.
  EXPECT_EQ(s.status, RunStatus::kAtRest);
  EXPECT_GT(s.impacts_ground() + s.impacts_interface(), 200);
  int settled = 0;
  for (const Event& e : runs[0].result.history.events) {
    settled += e.note.find("settled") != std::string::npos;
  }
  EXPECT_GT(settled, 10);
  ExpectSimilar(runs[0], runs[1], duration, "Rinaldi 228 x 0.7, k = 0.01");
  ExpectSimilar(runs[0], runs[2], duration, "Rinaldi 228 x 0.7, k = 100");
}

// An analytic motion: the thesis's free rocking (0.15 rad) until it settles, then a sine pulse
// of 0.6 g, 2 Hz at 6 s restarts it. The scaled runs get f / sqrt(k) and t0 sqrt(k): this
// checks the scans at rest and the step bounds tied to the motion's period.
TEST(SimilarityTest, FreeRockingRestAndRestartByAPulseScaleWithSqrtK) {
  const double duration = 12.0;
  std::vector<ScaledRun> runs;
  for (const double k : {1.0, 0.01, 100.0}) {
    Scene sc = ThesisStack(k);
    const double sk = std::sqrt(k);
    sc.initial = testing_util::Initial(0.15, 0.15, 0.0, 0.0);
    sc.run.duration_s = duration * sk;
    sc.run.output_interval_s = 0.01 * sk;
    MotionDef pulse;
    pulse.key = "base.horizontal";
    pulse.kind = MotionKind::kSinePulse;
    pulse.amplitude_g = 0.6;
    pulse.frequency_hz = 2.0 / sk;
    pulse.start_s = 6.0 * sk;
    sc.horizontal = pulse;
    runs.push_back({sk, Simulate(sc, GroundMotion::FromScene(sc))});
  }
  const Summary& s = runs[0].result.summary;
  EXPECT_GT(s.impacts_ground() + s.impacts_interface(), 100);
  EXPECT_EQ(s.initiations, 1);  // the restart by the pulse
  ExpectSimilar(runs[0], runs[1], duration, "free rocking + pulse, k = 0.01");
  ExpectSimilar(runs[0], runs[2], duration, "free rocking + pulse, k = 100");
}

}  // namespace
}  // namespace rockbench::reference
