// The reference where its physics changes (issue 37): the impact that hands the run over to the
// unilateral model, chattering, undetermined impacts. Each case is checked against an
// independent formulation written here (coulomb_impact.h), not against the production code.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "motion/ground_motion.h"
#include "reference/boundary_scenes.h"
#include "reference/coulomb_impact.h"
#include "reference/simulate.h"
#include "reference/unilateral/unilateral.h"
#include "scene/scene.h"

namespace rockbench::reference {
namespace {

using test::CoulombImpact;
using test::ImpactBlock;
using test_scenes::ThreeBlocks;
using test_scenes::ThreeBlocksWithFriction;

Scene Shipped(const std::string& name) {
  Scene s = LoadScene(std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/" + name + ".toml");
  s.compare.members = 0;
  return s;
}

// The scene at compare's witness settings (run/reference_witness.h, WitnessModel): dop853 at
// rtol 1e-14, atol 1e-16.
Scene Witness(const Scene& s) {
  Scene w = s;
  w.model.integrator = Integrator::kDop853;
  w.model.rtol = 1e-14;
  w.model.atol = 1e-16;
  return w;
}

std::vector<ImpactBlock> BlocksOf(const Scene& s) {
  return test_scenes::BlocksOf<ImpactBlock>(s);
}

// The mass centres and angles of a pivot chain (each block on its support's corner on the side
// its configuration letter names, 'f' on the right corner at a zero relative angle), written
// here from the geometry: block k's pivot is its base corner on side s_k, which sits on the
// support's top face at the support's corner offset s_k b_k from the face's middle.
Eigen::VectorXd ChainPositions(const std::vector<ImpactBlock>& blocks, const Configuration& c,
                               const Eigen::VectorXd& theta) {
  const int n = static_cast<int>(blocks.size());
  Eigen::VectorXd q(3 * n);
  auto turn = [](double th, double x, double y) {
    return Eigen::Vector2d(std::cos(th) * x + std::sin(th) * y,
                           -std::sin(th) * x + std::cos(th) * y);
  };
  Eigen::Vector2d top_mid(0.0, 0.0);  // the support's top-face middle
  double th_below = 0.0;
  for (int k = 0; k < n; ++k) {
    const double s = c[k] == Contact::kLeft ? -1.0 : 1.0;
    const Eigen::Vector2d pivot = top_mid + turn(th_below, s * blocks[k].b, 0.0);
    const Eigen::Vector2d g = pivot + turn(theta[k], -s * blocks[k].b, blocks[k].h);
    q.segment(3 * k, 3) << g.x(), g.y(), theta[k];
    top_mid = g + turn(theta[k], 0.0, blocks[k].h);
    th_below = theta[k];
  }
  return q;
}

// The chain's velocities: d q / d theta times the rates (central differences, step 1e-7 rad:
// error ~1e-14 from truncation, ~1e-9 relative from rounding).
Eigen::VectorXd ChainVelocities(const std::vector<ImpactBlock>& blocks, const Configuration& c,
                                const Eigen::VectorXd& theta, const Eigen::VectorXd& omega) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3 * static_cast<int>(blocks.size()));
  const double step = 1e-7;
  for (int i = 0; i < theta.size(); ++i) {
    Eigen::VectorXd a = theta, b = theta;
    a[i] += step;
    b[i] -= step;
    v += (ChainPositions(blocks, c, a) - ChainPositions(blocks, c, b)) / (2 * step) * omega[i];
  }
  return v;
}

// Issue 37, case 1: the thesis's stack with mu = 0.6 at both interfaces under Rinaldi 228 with
// its vertical component (scenes/rinaldi_with_vertical.toml). Its first slip comes at a ground
// impact whose no-slip impulse leaves block 1's friction cone: the run is handed over to the
// unilateral model just before that impact, and the impact is Coulomb's. The post-impact rates
// equal those of the independent Coulomb impact (coulomb_impact.h) from the same pre-impact
// state, to 1e-7 of the rates' scale: the independent Jacobians are central differences good to
// ~1e-9 (coulomb_impact.h), both sides' contact conditions hold to 1e-8 or better, and the
// impact is a linear solve with a condition number below 1e2 here. The no-slip outcome (the
// same solver at infinite friction) differs from it by more than 10% of the rates' scale: a
// model that resolved the impact without friction fails this test.
void CheckHandOverImpact(const Scene& s) {
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  const History& h = r.history;
  size_t at = 0;
  for (; at < h.events.size(); ++at) {
    if (h.events[at].note.rfind("unilateral model from here", 0) == 0) break;
  }
  ASSERT_LT(at + 1, h.events.size()) << "no hand-over";
  const Event& handover = h.events[at];
  const Event& impact = h.events[at + 1];
  EXPECT_NE(handover.note.find("impact"), std::string::npos) << handover.note;
  EXPECT_NE(impact.kind.find("_impact"), std::string::npos) << impact.kind;
  ASSERT_EQ(impact.t_s, handover.t_s);
  const std::vector<ImpactBlock> blocks = BlocksOf(s);
  const int n = static_cast<int>(blocks.size());
  Eigen::VectorXd theta(n), omega(n);
  const Sample x = r.trajectory.At(handover.t_s);
  for (int i = 0; i < n; ++i) {
    theta[i] = x.theta_rad[i];
    omega[i] = handover.omega_before_radps[i];
  }
  const Eigen::VectorXd q = ChainPositions(blocks, handover.mode_before, theta);
  const Eigen::VectorXd v = ChainVelocities(blocks, handover.mode_before, theta, omega);
  const test::CoulombImpactResult coulomb = CoulombImpact(blocks, q, v, 1e-9);
  ASSERT_EQ(coulomb.outcomes.size(), 1u);
  double scale = 0.0;
  for (int i = 0; i < n; ++i) scale += std::abs(omega[i]);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(impact.omega_after_radps[i], coulomb.outcomes[0][3 * i + 2], 1e-7 * scale)
        << "block " << i + 1;
  }
  // Some interface slips in Coulomb's outcome, and the no-slip outcome is another motion.
  bool slips = false;
  for (const int st : coulomb.states[0]) slips = slips || std::abs(st) == 2;
  EXPECT_TRUE(slips);
  std::vector<ImpactBlock> sticky = blocks;
  for (ImpactBlock& b : sticky) b.mu = std::numeric_limits<double>::infinity();
  const test::CoulombImpactResult no_slip = CoulombImpact(sticky, q, v, 1e-9);
  ASSERT_EQ(no_slip.outcomes.size(), 1u);
  double differ = 0.0;
  for (int i = 0; i < n; ++i) {
    differ =
        std::max(differ, std::abs(no_slip.outcomes[0][3 * i + 2] - impact.omega_after_radps[i]));
  }
  EXPECT_GT(differ, 0.1 * scale);
}

TEST(HandOverImpact, IsCoulombsImpactFromThePreImpactState) {
  CheckHandOverImpact(Shipped("rinaldi_with_vertical"));
}

// Three blocks (0.8 x 0.8, 0.6 x 0.6 and 0.4 x 0.8 m, mu = 0.5 at every interface) under
// Rinaldi 228: the N-block chain hands over at a ground impact (2.4436 s) whose no-slip impulse
// needs |P_T| / P_N = 0.70; the same check as above.
TEST(HandOverImpact, ThreeBlockChainHandsOverAtItsFirstSlippingImpact) {
  CheckHandOverImpact(ThreeBlocksWithFriction());
}

// The same scene from t = 0 in the unilateral model (model.formulation = "unilateral") is a
// second formulation of the same physics: before the hand-over it integrates maximal
// coordinates where the chain integrates angles, and both are exact to rtol 1e-12. With the
// hand-over impact resolved by Coulomb's law the two runs agree to 7.7e-9 rad up to block 2's
// overturn and overturn 3e-9 s apart (measured; the same run at rtol 1e-13 moves by 4e-12
// rad). Bounds: 1e-6 rad and 1e-6 s, 100 times that, and four orders below what resolving the
// hand-over impact without friction gave (2.5e-2 rad, 12 ms late).
TEST(HandOverImpact, DefaultRunFollowsTheUnilateralModelFromTheStart) {
  const Scene s = Shipped("rinaldi_with_vertical");
  Scene uni = s;
  uni.model.formulation = Formulation::kUnilateral;
  const GroundMotion gm = GroundMotion::FromScene(s);
  const Result a = Simulate(s, gm), b = Simulate(uni, gm);
  ASSERT_EQ(a.summary.status, RunStatus::kOverturned);
  ASSERT_EQ(b.summary.status, RunStatus::kOverturned);
  EXPECT_EQ(a.summary.overturn_block, b.summary.overturn_block);
  EXPECT_NEAR(a.summary.overturn_t_s, b.summary.overturn_t_s, 1e-6);
  double worst = 0.0;
  const double end = std::min(a.summary.overturn_t_s, b.summary.overturn_t_s) - 0.01;
  for (double t = 0.0; t <= end; t += 0.001) {
    const Sample x = a.trajectory.At(t), y = b.trajectory.At(t);
    for (int i = 0; i < x.blocks(); ++i) {
      worst = std::max(worst, std::abs(x.theta_rad[i] - y.theta_rad[i]));
    }
  }
  EXPECT_LT(worst, 1e-6);
}

// Issue 37, case 2: the three-block stack chatters at 6.79 s (within 1.1 ms: 13 ground and
// interface impacts, 15 slip stops, slips starting from rest at zero slip rate). The reference
// runs through it to the end of the run (it stopped there with "event cascade at one instant":
// a slip from rest whose rate of ~1e-18 m/s rounded the wrong way was taken for its end, and
// the same mode was found again at the same instant). Checks: the run completes; no impact adds
// energy; and the witness (dop853 at rtol 1e-14, a different integrator and tolerance) agrees
// with it to 1e-6 rad over the whole run (measured: 1.2e-8 rad, at 3.93 s).
TEST(Chattering, TheUnilateralModelRunsThroughAnImpactCascade) {
  const Scene s = ThreeBlocksWithFriction();
  const Scene w = Witness(s);
  const GroundMotion gm = GroundMotion::FromScene(s);
  const Result a = Simulate(s, gm), b = Simulate(w, gm);
  for (const Result* r : {&a, &b}) {
    EXPECT_TRUE(r->summary.status == RunStatus::kCompleted ||
                r->summary.status == RunStatus::kAtRest)
        << r->summary.status << ": " << r->summary.status_detail;
    EXPECT_NEAR(r->trajectory.end_s(), s.run.duration_s, 1e-9);
    EXPECT_EQ(r->summary.impacts_energy_gain, 0);
  }
  // The cascade is there: more than 10 events within 2 ms around 6.79 s.
  int cascade = 0;
  for (const Event& e : a.history.events) cascade += std::abs(e.t_s - 6.7902) < 1e-3;
  EXPECT_GT(cascade, 10);
  double worst = 0.0;
  for (double t = 0.0; t <= s.run.duration_s; t += 0.001) {
    const Sample x = a.trajectory.At(t), y = b.trajectory.At(t);
    for (int i = 0; i < x.blocks(); ++i) {
      worst = std::max(worst, std::abs(x.theta_rad[i] - y.theta_rad[i]));
    }
  }
  EXPECT_LT(worst, 1e-6);
}

// Two blocks released from rest at 0.15 rad each, no base motion (a scene the fuzzer found): the
// run hands over to the unilateral model at 0.576 s (an interface impulse that would pull) and
// rocks down to rest. It rocked for ever at 2e-10 rad instead (405 633 impacts in 10 s): each
// landing was located half the gap tolerance (1e-10 L) inside its face and the projection back
// onto the face raised the stack, adding m g gap_tol / 2 (5.5e-6 J here) per landing, more than
// a cascade's last impacts dissipate. Landings are now located where the gap is zero. Checks,
// with no base motion: between events the energy (kinetic in the base frame plus m g y) never
// grows by more than 1e-12 W L (the integration's tolerance, rtol 1e-12, on the potential
// energy; measured: it never grows, the projection only removes drift), and the cascade ends at
// rest in finitely many impacts (measured 109, at rest at 3.822 s).
TEST(Chattering, AFreeRockingStackComesToRestWithoutGainingEnergy) {
  const Scene s = ParseScene(
      "[block1]\nwidth = 1.35\nheight = 0.65\nmass = 7813.25\n"
      "[block2]\nwidth = 1.0\nheight = 2.5\nmass = 5403.0\n"
      "[initial]\ntheta1 = 0.15\ntheta2 = 0.15\n[run]\nduration = 5.0\n",
      std::string(ROCKBENCH_SOURCE_DIR) + "/free_rocking_pair.toml");
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  ASSERT_TRUE(r.summary.unilateral_from_s.has_value());
  EXPECT_EQ(r.summary.status, RunStatus::kAtRest) << r.summary.status_detail;
  EXPECT_LT(r.summary.impacts(), 1000);
  EXPECT_EQ(r.summary.impacts_energy_gain, 0);
  const UnilateralStack stack = UnilateralStack::OfScene(s);
  const double tol_j = 1e-12 * stack.weight_n() * stack.length_scale_m();
  double worst_j = -1.0;
  const Event* prev = nullptr;
  for (const Event& e : r.history.events) {
    if (e.t_s < *r.summary.unilateral_from_s) continue;
    if (prev != nullptr) worst_j = std::max(worst_j, e.energy_before_j - prev->energy_after_j);
    prev = &e;
  }
  EXPECT_LE(worst_j, tol_j);
}

// The stress catalogue's mass-ratio case (the thesis's stack with m2 = 0.001 m1, released at
// 0.39 rad) at rest_rate_rel 1e-9 and rtol 1e-14 (RestThresholdTest's run b's witness): block 1
// chatters on the ground under the rocking top block, its rate falling by 4 at each impact down
// to 2e-8 rad/s, where it stayed: 72 313 impacts 4.5 ns apart in 1.4 ms, the run never ended.
// At that rate the corner's motion is below the rounding of a gap (a few eps L: maximal
// coordinates of size L), which each landing rounds up into new energy. The rest speed is
// therefore never below the speed of a fall through 4 eps L (UnilateralStack::RestSpeed): the
// run overturns (block 2, 1.2 s) after 12 impacts, as at the default threshold.
TEST(Chattering, BelowWhatMaximalCoordinatesResolveTheStackComesToRest) {
  Scene s = ParseScene(
      "[block1]\nwidth = 1.25\nheight = 1.25\ndensity = 2500.0\n"
      "[block2]\nwidth = 1.0\nheight = 2.5\nmass = 3.90625\n"
      "[initial]\ntheta1 = 0.39\ntheta2 = 0.39\n[run]\nduration = 5.0\n"
      "[model]\nrest_rate_rel = 1e-9\nrtol = 1e-14\natol = 1e-16\n",
      std::string(ROCKBENCH_SOURCE_DIR) + "/mass_ratio.toml");
  s.compare.members = 0;
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  ASSERT_TRUE(r.summary.unilateral_from_s.has_value());
  EXPECT_EQ(r.summary.status, RunStatus::kOverturned) << r.summary.status_detail;
  EXPECT_LT(r.summary.impacts(), 100);
  EXPECT_EQ(r.summary.impacts_energy_gain, 0);
}

// Issue 37, case 4: three blocks (0.8 x 0.8, 0.6 x 0.6, 0.4 x 0.8 m, infinite friction) under
// Rinaldi 228 x 1.167. Handed over to the unilateral model at 2.5406 s (a contact that would
// pull), the stack's interface-2 impact at 2.642351 s has two admissible outcomes that give
// different motions, and the run says so (summary.undetermined). Checked against the
// independent Coulomb impact (coulomb_impact.h: full enumeration of the contact states) from
// the same pre-impact state: it too finds more than one admissible outcome, apart by more than
// the 1e-4 of the rates' scale within which the model takes two outcomes for one motion
// (measured: two outcomes 1.6e-3 apart on a scale of 1.17, 14 times that), and the outcome the
// model chose is one of them to 1e-6 of that scale (the independent solver's own distinctness
// threshold; its Jacobians are good to 1e-9; measured 9.6e-11).
TEST(UndeterminedImpact, HasTwoIndependentOutcomesAndTheRunTookOne) {
  const Scene s = ParseScene(
      "[[block]]\nwidth = 0.8\nheight = 0.8\ndensity = 2500.0\n"
      "[[block]]\nwidth = 0.6\nheight = 0.6\ndensity = 2500.0\n"
      "[[block]]\nwidth = 0.4\nheight = 0.8\ndensity = 2500.0\n"
      "[base.horizontal]\nfile = \"records/northridge1994_rinaldi_receiving_sta_228.AT2\"\n"
      "scale = 1.167\n[run]\nduration = 2.7\n",
      std::string(ROCKBENCH_SOURCE_DIR) + "/three_blocks.toml");
  const Result r = Simulate(s, GroundMotion::FromScene(s));
  ASSERT_TRUE(r.summary.undetermined_from_s.has_value());
  const double t = *r.summary.undetermined_from_s;
  const Event* impact = nullptr;
  for (const Event& e : r.history.events) {
    if (e.t_s == t && e.kind.find("_impact") != std::string::npos) impact = &e;
  }
  ASSERT_NE(impact, nullptr) << "no impact at " << t;
  EXPECT_NE(impact->note.find("2 impact outcomes"), std::string::npos) << impact->note;
  const std::vector<double> pre = r.trajectory.StateAt(t, true);
  const std::vector<double> post = r.trajectory.StateAt(t, false);
  const std::vector<ImpactBlock> blocks = BlocksOf(s);
  const int n = static_cast<int>(blocks.size());
  ASSERT_EQ(pre.size(), static_cast<size_t>(6 * n));
  ASSERT_EQ(post.size(), pre.size());
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(pre.data(), 3 * n);
  const Eigen::VectorXd v_minus = Eigen::Map<const Eigen::VectorXd>(pre.data() + 3 * n, 3 * n);
  const Eigen::VectorXd v_plus = Eigen::Map<const Eigen::VectorXd>(post.data() + 3 * n, 3 * n);
  // The pre-impact rates are the event's.
  for (int i = 0; i < n; ++i) {
    EXPECT_DOUBLE_EQ(v_minus[3 * i + 2], impact->omega_before_radps[i]);
  }
  // Every corner within the model's gap tolerance (1e-10 of the largest half-diagonal).
  const double L = std::hypot(0.2, 0.4);
  const test::CoulombImpactResult c = CoulombImpact(blocks, q, v_minus, 1e-10 * L);
  double v_scale = 0.0;
  for (int i = 0; i < 3 * n; ++i) v_scale = std::max(v_scale, std::abs(v_minus[i]));
  ASSERT_GE(c.outcomes.size(), 2u);
  double widest = 0.0, nearest = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < c.outcomes.size(); ++a) {
    nearest = std::min(nearest, (c.outcomes[a] - v_plus).cwiseAbs().maxCoeff());
    for (size_t b = 0; b < a; ++b) {
      widest = std::max(widest, (c.outcomes[a] - c.outcomes[b]).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(widest, 1e-4 * v_scale);
  EXPECT_LT(nearest, 1e-6 * v_scale);
  std::printf(
      "undetermined impact at %.9f s: %zu independent outcomes, %.3g apart (v scale "
      "%.3g), the run's %.3g from the nearest\n",
      t, c.outcomes.size(), widest, v_scale, nearest);
}

// A statue on a plinth on a pedestal (1.0 x 1.1, 0.7 x 0.2, 0.4 x 1.5 m; mu = 0.5 at every
// interface) under El Centro 1940 x 4.5455. At dop853 rtol 1e-14 the chain's friction margin is
// exactly zero on the far side of a located root at 1.685 s; taken for a face opening, the same
// configuration was found again at the same instant until the cascade guard stopped the run,
// while the default run (dopri5, 1e-12) overturned at 4.772 s: the comparison then used the
// stopped run. A margin at zero is the friction's, and both runs hand over and overturn at the
// same instant (to 1e-6 s: both are exact to their tolerances, measured 6e-10 rad apart).
TEST(Chattering, AFrictionMarginOfExactlyZeroHandsOver) {
  const Scene s = ThreeBlocks({1.0, 1.1, 0.7, 0.2, 0.4, 1.5},
                              "imperialvalley1940_elcentro_array9_180_PEER2000.AT2", 4.5455);
  const Scene w = Witness(s);
  const GroundMotion gm = GroundMotion::FromScene(s);
  const Result a = Simulate(s, gm), b = Simulate(w, gm);
  ASSERT_EQ(a.summary.status, RunStatus::kOverturned) << a.summary.status_detail;
  ASSERT_EQ(b.summary.status, RunStatus::kOverturned) << b.summary.status_detail;
  EXPECT_EQ(a.summary.overturn_block, b.summary.overturn_block);
  EXPECT_NEAR(a.summary.overturn_t_s, b.summary.overturn_t_s, 1e-6);
}

}  // namespace
}  // namespace rockbench::reference
