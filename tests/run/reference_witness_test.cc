// The reference's convergence check: the witness's settings, the difference between a run and
// its witness, the verdict "converged", and what a run does when it is not (the witness is used).
#include "run/reference_witness.h"

#include <gtest/gtest.h>

#include <cmath>

#include "motion/ground_motion.h"
#include "run/engine_run.h"
#include "tests/common/housner_scene.h"

namespace rockbench {
namespace {

// The thesis's free-rocking example (6.3.1): two blocks released together from 0.15 rad.
Scene ThesisFreeRocking() {
  Scene s;
  s.blocks = {{1.25, 1.25, 1.0, 2500.0 * 1.25 * 1.25, 2500.0}};
  s.blocks.resize(1);
  s.blocks.push_back(BlockDef{1.0, 2.5, 1.0, 2500.0 * 2.5, 2500.0});
  s.initial.theta_rad[0] = s.initial.theta_rad[1] = 0.15;
  s.run.duration_s = 6.0;
  return s;
}

TEST(WitnessModel, IsTighterByTheSchemesOrder) {
  ModelConfig m;
  m.rtol = 1e-9;
  m.atol = 1e-11;
  const ModelConfig w = WitnessModel(m);
  EXPECT_DOUBLE_EQ(w.rtol, 1e-11);
  EXPECT_DOUBLE_EQ(w.atol, 1e-13);
  // The witness is the other Dormand-Prince pair: a pair's own run at rtol / 100 can be the
  // same run.
  EXPECT_EQ(w.integrator, Integrator::kDop853);
  m.integrator = Integrator::kDop853;
  EXPECT_EQ(WitnessModel(m).integrator, Integrator::kDopri5);
  EXPECT_DOUBLE_EQ(WitnessModel(m).rtol, 1e-11);
  m.integrator = Integrator::kRk4;
  m.step_s = 1e-3;
  EXPECT_EQ(WitnessModel(m).step_s, 2.5e-4);
  m.events = EventScheme::kThesis;
  EXPECT_EQ(WitnessModel(m).step_s, 1e-4);
}

TEST(Convergence, TheDefaultToleranceIsConvergedOnTheThesisExample) {
  // Measured: 1.6e-12 rad between rtol 1e-12 and 1e-14 over the 6 s and ~215 impacts; the
  // bound 1e-9 rad is 0.1% of a Bullet error at dt 1e-4 s (6e-4 rad): "well below".
  const Scene s = ThesisFreeRocking();
  const CheckedReference r = RunCheckedReference(s, GroundMotion());
  ASSERT_TRUE(r.check.has_value());
  EXPECT_TRUE(r.check->converged);
  EXPECT_FALSE(r.check->diverges_at_s.has_value());
  EXPECT_LT(r.check->max_abs_diff(), 1e-9);
  EXPECT_EQ(&r.used(), &r.nominal);
}

TEST(Convergence, ALooseReferenceIsCaughtAndTheWitnessIsUsed) {
  // The thesis's event scheme at 20 ms sees each impact up to a step late: the first impacts
  // move by up to 20 ms and theta2 by far more than 10% of its peak (measured 0.06-0.2 rad).
  Scene s = ThesisFreeRocking();
  s.model.integrator = Integrator::kRk4;
  s.model.events = EventScheme::kThesis;
  s.model.step_s = 0.02;
  const CheckedReference r = RunCheckedReference(s, GroundMotion());
  ASSERT_TRUE(r.check.has_value());
  EXPECT_FALSE(r.check->converged);
  ASSERT_TRUE(r.check->diverges_at_s.has_value());
  // Before the first impact (0.6 s) both schemes integrate the same smooth motion.
  EXPECT_GT(*r.check->diverges_at_s, 0.3);
  EXPECT_GT(r.check->max_abs_diff(), r.check->tolerance_rad[1]);
  EXPECT_EQ(&r.used(), &*r.witness);
  const nlohmann::json j = ConvergenceJson(s, *r.check);
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["used"], "witness");
  EXPECT_EQ(j["witness"]["step_s"], 0.002);
  EXPECT_NE(ConvergenceWarning(*r.check).find("NOT converged"), std::string::npos);

  // `run` (RunEngine) reports it and writes the witness's history.
  const EngineRun run = RunEngine("reference", s, GroundMotion());
  EXPECT_FALSE(run.summary["convergence"]["converged"].get<bool>());
  EXPECT_EQ(run.history.samples.size(), r.witness->history.samples.size());
  EXPECT_NE(run.one_line.find("NOT converged"), std::string::npos);
}

TEST(Convergence, RunsWithoutTheWitnessWhenNotAsked) {
  const Scene s = testing_util::HousnerHalfAngleRelease(2.0);
  const CheckedReference r = RunCheckedReference(s, GroundMotion(), false);
  EXPECT_FALSE(r.check.has_value());
  EXPECT_FALSE(r.witness.has_value());
  const EngineRun run = RunEngine("reference", s, GroundMotion(), {.check_convergence = false});
  EXPECT_FALSE(run.summary.contains("convergence"));
}

// N >= 3 blocks (issue 23): two squat, heavy drums that never lift and a slender block 3 rocking
// on them from theta3 = `theta3` (rad).
Scene TopBlockRocks(double theta3) {
  Scene s;
  s.blocks = {BlockDef{3.0, 0.5, 1.0, 3750.0, 2500.0}, BlockDef{3.0, 0.5, 1.0, 3750.0, 2500.0},
              BlockDef{0.4, 1.2, 1.0, 1200.0, 2500.0}};
  s.initial.theta_rad[2] = theta3;
  s.run.duration_s = 2.0;
  return s;
}

// Every block is compared with its witness: a run against itself differs by exactly nothing on
// any block; against a run whose block 3 starts 0.02 rad further (blocks 1 and 2 stay exactly at
// rest in both), block 3 alone differs, by 0.02 rad at t = 0 (more than its tolerance, 10% of
// its 0.1 rad peak), and the check diverges there. summary.json's convergence names theta3.
TEST(Convergence, EveryBlockOfAStackIsCompared) {
  const Scene s = TopBlockRocks(0.1);
  const reference::Result nominal = reference::Simulate(s, GroundMotion());
  ASSERT_EQ(nominal.summary.peak_theta_rad[0], 0.0);
  const ConvergenceCheck same = CompareWithWitness(s, nominal, nominal);
  ASSERT_EQ(same.max_abs_diff_rad.size(), 3u);
  ASSERT_EQ(same.tolerance_rad.size(), 3u);
  for (int b = 0; b < 3; ++b) EXPECT_EQ(same.max_abs_diff_rad[b], 0.0) << b;
  EXPECT_TRUE(same.converged);
  EXPECT_DOUBLE_EQ(same.tolerance_rad[2], 0.1 * 0.1);

  const reference::Result other = reference::Simulate(TopBlockRocks(0.12), GroundMotion());
  const ConvergenceCheck c = CompareWithWitness(s, nominal, other);
  EXPECT_EQ(c.max_abs_diff_rad[0], 0.0);
  EXPECT_EQ(c.max_abs_diff_rad[1], 0.0);
  // At least the initial 0.02 rad (the two rock apart afterwards, by up to their peaks).
  EXPECT_GE(c.max_abs_diff_rad[2], 0.02 - 1e-15);
  EXPECT_LE(c.max_abs_diff_rad[2], 0.25);
  EXPECT_EQ(c.max_abs_diff(), c.max_abs_diff_rad[2]);
  ASSERT_TRUE(c.diverges_at_s.has_value());
  EXPECT_EQ(*c.diverges_at_s, 0.0);
  EXPECT_FALSE(c.converged);
  const nlohmann::json j = ConvergenceJson(s, c);
  for (const char* th : {"theta1", "theta2", "theta3"}) {
    EXPECT_TRUE(j["max_abs_diff_rad_per_block"][th].is_number()) << th;
    EXPECT_TRUE(j["tolerance_rad"][th].is_number()) << th;
  }
  EXPECT_EQ(j["max_abs_diff_rad_per_block"]["theta3"], c.max_abs_diff_rad[2]);
  EXPECT_FALSE(j["max_abs_diff_rad_per_block"].contains("theta4"));
  // One and two blocks keep their keys: theta1 (and theta2) only.
  const Scene housner = testing_util::HousnerHalfAngleRelease(1.0);
  const reference::Result h = reference::Simulate(housner, GroundMotion());
  const nlohmann::json jh = ConvergenceJson(housner, CompareWithWitness(housner, h, h));
  EXPECT_EQ(jh["max_abs_diff_rad_per_block"].size(), 1u);
}

}  // namespace
}  // namespace rockbench
