// The reference driver on N blocks (issue 23): the chain formulation against the thesis's for
// one and two blocks, closed forms for a locked column of N drums, energy conserved between
// impacts and never gained across them for N up to 10, and tipping from rest at the closed-form
// threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/outcome.h"
#include "motion/ground_motion.h"
#include "reference/benchmarks/closed_forms.h"
#include "reference/chain/stack_chain.h"
#include "reference/simulate.h"
#include "scene/mode.h"

namespace rockbench::reference {
namespace {

// A stack of blocks (width, height, density), depth 1 m.
Scene Stack(const std::vector<std::array<double, 3>>& blocks, double duration_s = 4.0) {
  Scene sc;
  for (const auto& b : blocks) {
    sc.blocks.push_back({b[0], b[1], 1.0, b[2] * b[0] * b[1], b[2]});
  }
  sc.run.duration_s = duration_s;
  sc.run.output_interval_s = 0.01;
  return sc;
}

// The column of n equal drums (0.9 m x 0.85 m, marble).
Scene Column(int n, double duration_s = 4.0) {
  return Stack(std::vector<std::array<double, 3>>(n, {0.9, 0.85, 2700.0}), duration_s);
}

Result RunOn(Scene sc, const char* formulation) {
  sc.model.formulation = ParseFormulation(formulation).value();
  return Simulate(sc, GroundMotion::FromScene(sc));
}

TEST(StackSimulateTest, TheChainRunsTheThesisStackAsTheThesisEquationsDo) {
  // The thesis's free-rocking stack, 6 s, 37 impacts: the same events, the histories within
  // the rounding that 37 impacts amplify (measured: the thesis's own run moved by 1 ulp of its
  // initial angle differs by as much; see docs/n-blocks.md).
  Scene sc = Stack({{1.25, 1.25, 2500.0}, {1.0, 2.5, 2500.0}}, 6.0);
  sc.initial.theta_rad[0] = sc.initial.theta_rad[1] = 0.15;
  const Result a = RunOn(sc, "thesis"), b = RunOn(sc, "chain");
  ASSERT_EQ(a.history.events.size(), b.history.events.size());
  for (size_t i = 0; i < a.history.events.size(); ++i) {
    const Event &ea = a.history.events[i], &eb = b.history.events[i];
    EXPECT_EQ(ea.kind, eb.kind) << i;
    EXPECT_EQ(ea.mode_after, eb.mode_after) << i;
    EXPECT_NEAR(ea.t_s, eb.t_s, 1e-9) << i;
  }
  double diff = 0.0;
  for (double t = 0.0; t <= 6.0; t += 1e-3) {
    const Sample sa = a.trajectory.At(t), sb = b.trajectory.At(t);
    for (int k = 0; k < 2; ++k) diff = std::max(diff, std::abs(sa.theta_rad[k] - sb.theta_rad[k]));
  }
  std::printf("thesis free rocking, chain vs thesis equations: max |dtheta| %.3g rad\n", diff);
  EXPECT_LT(diff, 1e-9);
}

TEST(StackSimulateTest, OneBlockOnTheChainIsHousnersBlock) {
  // Released from theta0: the first impact at the closed-form time, the rate after it
  // Housner's restitution times the rate before.
  Scene sc = Stack({{0.5, 2.0, 2000.0}}, 3.0);
  sc.initial.theta_rad[0] = 0.1;
  const Result r = RunOn(sc, "chain");
  const benchmarks::RockingBody body = benchmarks::LockedColumn(sc);
  ASSERT_FALSE(r.history.events.empty());
  const Event& first = r.history.events[0];
  EXPECT_EQ(first.kind, "ground_impact");
  EXPECT_NEAR(first.t_s, benchmarks::FirstImpactTime_s(body, 0.1), 1e-9);
  EXPECT_NEAR(first.omega_before_radps[0], -benchmarks::FreeRockingImpactRate_radps(body, 0.1),
              1e-9);
  EXPECT_NEAR(first.omega_after_radps[0],
              first.omega_before_radps[0] * benchmarks::CornerImpactRestitution(body), 1e-12);
}

TEST(StackSimulateTest, ALockedColumnRocksAsOneBodyUntilItsFirstImpact) {
  // N drums tilted together: while every interface stays closed the column is one rocking
  // body, so the first impact comes at the closed-form time with the closed-form rate, for
  // every N.
  for (const int n : {1, 2, 3, 6, 10}) {
    Scene sc = Column(n, 3.0);
    const benchmarks::RockingBody body = benchmarks::LockedColumn(sc);
    const double theta0 = 0.5 * body.alpha_rad();
    for (int i = 0; i < n; ++i) sc.initial.theta_rad[i] = theta0;
    const Result r = RunOn(sc, "chain");
    ASSERT_FALSE(r.history.events.empty()) << n;
    const Event& first = r.history.events[0];
    EXPECT_EQ(first.kind, "ground_impact") << n << " drums: " << first.kind;
    const double t_want = benchmarks::FirstImpactTime_s(body, theta0);
    EXPECT_NEAR(first.t_s, t_want, 1e-9 * t_want) << n << " drums";
    const double w_want = benchmarks::FreeRockingImpactRate_radps(body, theta0);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(first.omega_before_radps[i], -w_want, 1e-9 * w_want) << n << " drums, " << i;
    }
  }
}

TEST(StackSimulateTest, FreeRockingConservesEnergyBetweenImpactsAndLosesItAtEach) {
  // Free rocking (no base motion): the energy of every recorded sample between two events
  // equals the energy at the last event, to the integrator's tolerance (rtol 1e-12 on angles of
  // 0.1 rad over a few thousand steps: 1e-9 of the energy is a wide bound); no event adds any.
  // Tilted together, the top drum a little further: the column rocks as one and its top drum
  // rocks on the one below. Three drums 0.85 m tall rock on each other at many interface
  // impacts; taller columns of such drums end in an impact with no admissible outcome within
  // 0.05 s (docs/n-blocks.md, "Where the model ends"), so 5 and 10 drums are 0.3 m tall (the
  // column rocks as one body, its top drum lands once, and it comes to rest within 4 s).
  struct Case {
    int n;
    double height_m;
  };
  for (const Case& k : {Case{3, 0.85}, Case{5, 0.3}, Case{10, 0.3}}) {
    const int n = k.n;
    Scene sc = Stack(std::vector<std::array<double, 3>>(n, {0.9, k.height_m, 2700.0}), 4.0);
    for (int i = 0; i < n; ++i) sc.initial.theta_rad[i] = 0.04;
    sc.initial.theta_rad[n - 1] = 0.045;
    const Result r = RunOn(sc, "chain");
    StackGeometry geo;
    geo.g = sc.run.gravity_mps2;
    for (const BlockDef& b : sc.blocks) {
      geo.blocks.push_back(MakeBlockProps(b.width_m, b.height_m, b.mass_kg));
    }
    StackChain chain(geo);
    auto energy = [&](const Sample& s) {
      chain.Place(s.mode, s.theta_rad.data(), s.omega_radps.data());
      return chain.Energy();
    };
    double e_ref = energy(r.history.samples.front()), worst = 0.0;
    size_t next_event = 0;
    int gains = 0;
    for (const Sample& s : r.history.samples) {
      while (next_event < r.history.events.size() && r.history.events[next_event].t_s <= s.t_s) {
        const Event& ev = r.history.events[next_event++];
        gains += ev.energy_after_j > ev.energy_before_j * (1 + 1e-12);
        e_ref = ev.energy_after_j;
      }
      worst = std::max(worst, std::abs(energy(s) - e_ref) / e_ref);
    }
    std::printf(
        "%d drums: %s (%s), %zu events, energy drift between events at most %.2g of the "
        "total\n",
        n, StatusText(r.summary.status), r.summary.status_detail.c_str(), r.history.events.size(),
        worst);
    EXPECT_LT(worst, 1e-9) << n;
    EXPECT_EQ(gains, 0) << n;
    EXPECT_EQ(r.summary.impacts_energy_gain, 0) << n;
    EXPECT_GT(r.summary.impacts(), 10) << n;
    // The whole 4 s inside the model (at rest counts: nothing moves after).
    EXPECT_TRUE(r.summary.status == RunStatus::kCompleted || r.summary.status == RunStatus::kAtRest)
        << n << ": " << StatusText(r.summary.status);
    EXPECT_EQ(r.summary.impacts_inadmissible, 0) << n;
    EXPECT_NEAR(r.history.samples.back().t_s, 4.0, 1e-12) << n;
  }
}

TEST(StackSimulateTest, AnImpactWhoseSearchReachesItsCapIsReportedAndEndsTheModel) {
  // A column at rest whose top drum, released from 0.02 rad, lands on it. Its landing opens
  // the interfaces below (docs/n-blocks.md, "Where the model ends"): the admissible outcome is
  // one with many changes, which the search (fewest changes first) reaches last. With
  // 10 drums every candidate is within the cap (2 x 3^9 = 39,366 of 59,049) and the landing is
  // admissible. With 21 (2 x 3^20) the search stops at the cap, and the run says so: the note,
  // the inadmissible count and `undetermined` at that impact. (Up to kUnilateralMaxBlocks = 20
  // drums an impact without an admissible chain outcome is the unilateral model's instead,
  // docs/sliding.md "The impact at a hand-over": 21 is the first column the chain keeps.)
  static_assert(kUnilateralMaxBlocks < 21);
  for (const int n : {10, 21}) {
    Scene sc = Column(n, 0.2);
    sc.initial.theta_rad[n - 1] = 0.02;
    const Result r = RunOn(sc, "chain");
    const Event* landing = nullptr;
    for (const Event& ev : r.history.events) {
      if (ev.kind.find("impact") != std::string::npos) {
        landing = &ev;
        break;
      }
    }
    ASSERT_NE(landing, nullptr) << n;
    EXPECT_EQ(landing->kind, InterfaceName(n - 1, n) + "_impact") << n;
    if (n == 10) {
      EXPECT_EQ(landing->note.find("inadmissible"), std::string::npos) << landing->note;
      // The interfaces below open: measured fllllllllf, the landing one closing and the ground
      // kept closed by the rest rule (the note says "settled"). Eight changes from the
      // baseline: the search's last depths.
      EXPECT_GE(landing->mode_after.open_count(), n - 2) << ConfigurationName(landing->mode_after);
      // The landing itself is decided: anything undecided comes later (since issue 37 the
      // column's later impacts without an admissible chain outcome are the unilateral model's).
      if (r.summary.undetermined_from_s) {
        EXPECT_GT(*r.summary.undetermined_from_s, landing->t_s);
      }
    } else {
      EXPECT_NE(landing->note.find("no admissible outcome among the first 59049 (search stopped)"),
                std::string::npos)
          << landing->note;
      EXPECT_GE(r.summary.impacts_inadmissible, 1);
      ASSERT_TRUE(r.summary.undetermined_from_s.has_value());
      EXPECT_EQ(*r.summary.undetermined_from_s, landing->t_s);
      EXPECT_NE(r.summary.undetermined_detail.find("no admissible outcome"), std::string::npos)
          << r.summary.undetermined_detail;
    }
    std::printf("%d drums: landing at %.4f s (%s), %d impacts, %d inadmissible, status %s\n", n,
                landing->t_s, landing->note.c_str(), r.summary.impacts(),
                r.summary.impacts_inadmissible, StatusText(r.summary.status));
  }
}

}  // namespace
}  // namespace rockbench::reference
