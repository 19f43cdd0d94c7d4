// Events inside one step: an event function (ground gap, interface gap, overturn margin, face
// and point contact margins, the initiation criterion at rest) that dips below zero and comes
// back within one integration step (or one scan at rest) must not be missed. Each case below
// had such a dip inside a step before the driver searched the steps' interiors: a grazing
// overturn in free rocking, uplift under a 50 Hz vertical motion near -g, and an initiation by
// a 50 Hz horizontal motion barely above the stack's uplift acceleration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "reference/benchmarks/closed_forms.h"
#include "reference/integration/integrator.h"
#include "reference/simulate.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/transitions.h"

namespace rockbench::reference {
namespace {

// The first place where an event function is negative inside a piece of the solution (a
// missed event), or "" when there is none: every trajectory segment is checked at 400
// interior points, in its own mode. A located event ends its segment, so inside a segment
// every function must stay >= 0 (to -1e-10: rad for the angles, units of the weight M g for
// the margins; the dips of the cases below are 5e-6 rad and 1e-4 to 6e-4 M g).
std::string FirstMissedEvent(const Scene& sc, const GroundMotion& gm, const Result& r) {
  const Geometry geo = MakeGeometry(sc);
  // The chain's segments only: from a hand-over on, the unilateral model's contacts rule.
  const double t_chain_end = r.summary.unilateral_from_s.value_or(r.trajectory.end_s());
  for (const auto& seg : r.trajectory.segments()) {
    if (!(seg.t1 > seg.t0) || seg.t0 >= t_chain_end) continue;
    const Mode mode = *ModeOfConfiguration(seg.mode);
    const Contacts c = ContactsOf(mode);
    const int n = 400;
    for (int k = 1; k < n; ++k) {
      const double t = seg.t0 + (seg.t1 - seg.t0) * k / n;
      // Inside the segment: its own interpolant (one block's theta2 mirrors theta1).
      const Sample smp = r.trajectory.At(t);
      const int top = geo.two_blocks ? 1 : 0;
      Vec4 y{smp.theta_rad[0], smp.theta_rad[top], smp.omega_radps[0], smp.omega_radps[top]};
      if (!geo.two_blocks || c.interface == Contact::kFace) {
        y[1] = y[0];
        y[3] = y[2];
      }
      if (c.ground == Contact::kFace) y[0] = y[2] = 0.0;
      const State s{y[0], y[1], y[2], y[3]};
      const ContactMargins cm =
          EvaluateContacts(geo, mode, s, gm.xg_mps2(t), gm.yg_mps2(t), sc.model.equations);
      const double side_g = c.ground == Contact::kLeft ? -1.0 : 1.0;
      const double side_i = c.interface == Contact::kLeft ? -1.0 : 1.0;
      const std::pair<const char*, double> fns[] = {
          {"ground gap", c.ground != Contact::kFace ? side_g * y[0] : 1.0},
          {"interface gap", geo.two_blocks && c.interface != Contact::kFace
                                ? side_i * (c.ground == Contact::kFace ? y[1] : y[1] - y[0])
                                : 1.0},
          {"overturn", sc.model.overturn_rad - std::max(std::abs(y[0]), std::abs(y[1]))},
          {"face margin", sc.model.check_transitions ? cm.face : 1.0},
          {"point margin", cm.point}};
      for (const auto& [name, v] : fns) {
        if (v < -1e-10) {
          return std::string(name) + " = " + std::to_string(v) + " at t = " + std::to_string(t) +
                 " s inside a " + std::string(ModeName(mode)) + " segment [" +
                 std::to_string(seg.t0) + ", " + std::to_string(seg.t1) + "]";
        }
      }
    }
  }
  return "";
}

// A block (B = 1 m, H = 4 m) launched upright at w0 = 0.3718 rad/s rises to the apex given by
// energy, cos(theta_c - apex) = cos(theta_c) + w0^2 / k, k = 1.5 g / r (0.1000006 rad), and
// falls back. With overturn_angle 5e-6 rad below the apex, |theta| exceeds it for 9 ms around
// the apex, inside one 20 ms step (free rocking is a near-polynomial arc: the steps are the
// largest allowed at any tolerance). The run must stop there, at the first crossing: where the
// same motion without the limit crosses that angle (a tight run, the crossing located on its
// dense output).
TEST(EventsTest, GrazingOverturnInsideOneStepIsFound) {
  Scene sc;
  sc.blocks = {{1.0, 4.0, 1.0, 10000.0, 2500.0}};
  sc.initial.omega_radps[0] = 0.3718;
  sc.run.duration_s = 3.0;
  sc.model.rtol = 1e-12;
  sc.model.atol = 1e-14;
  const Geometry geo = MakeGeometry(sc);
  const double apex = benchmarks::FreeRockingAmplitude_rad(
      benchmarks::RectangularBlock(geo.block1, geo.g), sc.initial.omega_radps[0]);
  const Result free = Simulate(sc, GroundMotion{});
  EXPECT_NEAR(free.summary.peak_theta_rad[0], apex, 1e-11);
  sc.model.overturn_rad = apex - 5e-6;
  // The crossing of the limit on the rising arc of the free run.
  auto f = [&](double t) { return free.trajectory.At(t).theta_rad[0] - sc.model.overturn_rad; };
  const double t_apex = free.summary.peak_theta_t_s[0];
  const double t_cross = BrentBracket(f, 0.0, t_apex, f(0.0), f(t_apex), 1e-14).second;
  for (const double rtol : {1e-6, 1e-9, 1e-12}) {
    SCOPED_TRACE("rtol " + std::to_string(rtol));
    sc.model.rtol = rtol;
    const Result r = Simulate(sc, GroundMotion{});
    EXPECT_EQ(FirstMissedEvent(sc, GroundMotion{}, r), "");
    EXPECT_EQ(r.summary.status, RunStatus::kOverturned);
    // The tight run's crossing is good to ~1e-12 s; the loose runs' arcs differ from it by
    // their own error (rtol 1e-6 on 0.1 rad over a rate of 0.013 rad/s near the crossing:
    // ~1e-5 s at most; measured 1e-10 s, the arc being nearly polynomial).
    EXPECT_NEAR(r.summary.overturn_t_s, t_cross, 1e-6);
  }
}

// A Housner block (B = 1 m, H = 4 m) released from 0.1 rad under a 50 Hz vertical motion of
// 0.999 g: at the troughs the ground's normal force, reduced by the rocking's centripetal and
// tangential terms, turns tensile for a fraction of a millisecond (the model's no-uplift
// assumption fails: the unilateral model takes over, issue 24). Steps are 0.3 to 5 ms (rtol
// 1e-12 to 1e-6), so the dips fall inside steps. The hand-over must come at the first dip, the
// same at every tolerance.
TEST(EventsTest, UpliftDipsUnderFastVerticalMotionAreFoundAtTheFirstOne) {
  Scene sc;
  sc.blocks = {{1.0, 4.0, 1.0, 10000.0, 2500.0}};
  sc.initial.theta_rad[0] = 0.1;
  sc.run.duration_s = 2.0;
  sc.model.atol = 1e-14;
  MotionDef v;
  v.key = "base.vertical";
  v.kind = MotionKind::kHarmonic;
  v.amplitude_g = 0.999;
  v.frequency_hz = 50.0;
  v.start_s = 0.0003;
  sc.vertical = v;
  const GroundMotion gm = GroundMotion::FromScene(sc);
  double t_first = -1.0;
  for (const double rtol : {1e-12, 1e-9, 1e-6}) {
    SCOPED_TRACE("rtol " + std::to_string(rtol));
    sc.model.rtol = rtol;
    const Result r = Simulate(sc, gm);
    EXPECT_EQ(FirstMissedEvent(sc, gm, r), "");
    ASSERT_TRUE(r.summary.unilateral_from_s.has_value());
    EXPECT_NE(r.summary.unilateral_reason.find("lift-off"), std::string::npos);
    const double t_stop = *r.summary.unilateral_from_s;
    if (t_first < 0.0) t_first = t_stop;
    // The same dip: its located start agrees to the loose runs' error, far below the 20 ms
    // between dips.
    EXPECT_NEAR(t_stop, t_first, 1e-5);
  }
}

// The thesis's stack at rest under a 50 Hz horizontal harmonic of 1.0001 times the stack's
// uplift acceleration g b1 / h_G: the criterion at rest is violated for 0.09 ms around each
// peak of |xg''| (every 10 ms), far less than the former 1 ms scan at rest (which caught the
// first peak only because its checks started at t0 and one fell on it, and missed the later
// ones once the stack had settled). The stack must start to rock at the first peak.
TEST(EventsTest, BriefExcursionAboveTheUpliftThresholdAtRestStartsMotion) {
  Scene sc;
  sc.blocks = {{1.25, 1.25, 1.0, 3906.25, 2500.0}};
  sc.blocks.resize(1);
  sc.blocks.push_back(BlockDef{1.0, 2.5, 1.0, 6250.0, 2500.0});
  sc.run.duration_s = 0.1;
  sc.model.rtol = 1e-12;
  sc.model.atol = 1e-14;
  const Geometry geo = MakeGeometry(sc);
  const double threshold_mps2 = geo.g * geo.block1.b / geo.h_stack;
  MotionDef h;
  h.key = "base.horizontal";
  h.kind = MotionKind::kHarmonic;
  h.amplitude_g = 1.0001 * threshold_mps2 / kStandardGravity_mps2;
  h.frequency_hz = 50.0;
  h.start_s = 0.0003;
  sc.horizontal = h;
  const GroundMotion gm = GroundMotion::FromScene(sc);
  const Result r = Simulate(sc, gm);
  EXPECT_EQ(FirstMissedEvent(sc, gm, r), "");
  ASSERT_GE(r.summary.initiations, 1);
  double t_init = -1.0;
  for (const Event& e : r.history.events) {
    if (e.kind == "initiation") {
      t_init = e.t_s;
      break;
    }
  }
  // The window above the threshold: the peak at t0 + 1/(4 f), half-width acos(1/1.0001) /
  // (2 pi f) = 45 us.
  const double t_peak = h.start_s + 0.25 / h.frequency_hz;
  const double half = std::acos(1.0 / 1.0001) / (2 * M_PI * h.frequency_hz);
  EXPECT_NEAR(t_init, t_peak - half, 1e-9);
}

}  // namespace
}  // namespace rockbench::reference
