// The monitor on synthetic states (no Bullet): angle read-back, mode inference, impacts with
// interpolated times and post-impact rates, output sampling, and the measures of what the model
// forbids (slip, uplift, penetration, energy growth, blow-up, overturning).
#include "engines/common/monitor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "engines/common/cylinder_world.h"
#include "scene/scene.h"
#include "scene/stack_pose.h"
#include "tests/common/initial_state.h"

namespace rockbench {
namespace {

// Single block B = 1 m, H = 4 m, 10 t; or the thesis's two blocks.
EngineInput Input(bool two, double dt = 1e-3, double out = 1e-3) {
  EngineInput in;
  if (two) {
    in.blocks = {{1.25, 1.25, 1.0, 3906.25, 0.0}, {1.0, 2.5, 1.0, 6250.0, 0.0}};
  } else {
    in.blocks = {{1.0, 4.0, 1.0, 10000.0, 0.0}};
  }
  in.time_step_s = dt;
  in.run.output_interval_s = out;
  in.run.duration_s = 1.0;
  in.steps = static_cast<std::int64_t>(std::llround(1.0 / dt));
  return in;
}

BodyReadout ToReadout(const PlanarPose& p) {
  return {p.x_m, p.y_m, std::cos(p.phi_rad), std::sin(p.phi_rad), p.vx_mps, p.vy_mps, p.w_radps};
}

// The readout of an exact pivot-chain state (what an ideal engine would produce).
StepReadout At(const EngineInput& in, double t, double th1, double w1, double th2 = 0.0,
               double w2 = 0.0) {
  const StackPlacement p = PlaceStack(in.blocks, testing_util::Initial(th1, th2, w1, w2));
  StepReadout r(in.block_count());
  r.t_s = t;
  for (int k = 0; k < in.block_count(); ++k) r.blocks[k] = ToReadout(p.blocks[k]);
  return r;
}

TEST(MonitorTest, ReadsAnglesBackInTheThesisConvention) {
  EngineInput in = Input(true);
  in.overturn_rad = 10.0;  // let the blocks turn past pi without stopping
  Monitor m(in);
  m.Start(At(in, 0.0, 0.1, -0.2, 0.15, 0.3));
  EXPECT_NEAR(m.last().theta_rad[0], 0.1, 1e-15);
  EXPECT_NEAR(m.last().theta_rad[1], 0.15, 1e-15);
  EXPECT_NEAR(m.last().omega_radps[0], -0.2, 1e-15);
  EXPECT_NEAR(m.last().omega_radps[1], 0.3, 1e-15);
  EXPECT_EQ(ModeOfConfiguration(m.last().mode), Mode::k1a);
  // Angles are unwrapped: a block turned past pi keeps counting.
  m.Step(1, At(in, 1e-3, 3.0, 0.0, 3.0, 0.0));
  m.Step(2, At(in, 2e-3, 3.3, 0.0, 3.3, 0.0));
  EXPECT_NEAR(m.last().theta_rad[0], 3.3, 1e-12);
}

TEST(MonitorTest, InfersEveryModeFromTheState) {
  struct Case {
    double th1, w1, th2, w2;
    Mode mode;
  };
  // Angles well beyond the 1e-5 rad threshold; a flat block turning faster than 1e-2 rad/s is
  // passing through zero towards the side of its rate.
  const Case cases[] = {
      {0.1, 0, 0.15, 0, Mode::k1a},    {-0.1, 0, -0.15, 0, Mode::k1b},
      {0.1, 0, 0.05, 0, Mode::k2a},    {-0.1, 0, -0.05, 0, Mode::k2b},
      {0.1, 0, 0.1, 0, Mode::k3a},     {-0.1, 0, -0.1, 0, Mode::k3b},
      {0.0, 0, 0.1, 0, Mode::k4a},     {0.0, 0, -0.1, 0, Mode::k4b},
      {0.0, 0, 0.0, 0, Mode::kRest},   {2e-6, 1e-3, 2e-6, 1e-3, Mode::kRest},
      {0.0, 0.5, 0.0, 0.5, Mode::k3a}, {0.0, -0.5, 0.0, -0.5, Mode::k3b},
  };
  const EngineInput in = Input(true);
  for (const Case& c : cases) {
    Monitor m(in);
    m.Start(At(in, 0.0, c.th1, c.w1, c.th2, c.w2));
    EXPECT_EQ(ModeOfConfiguration(m.last().mode), c.mode) << c.th1 << " " << c.th2 << " " << c.w1;
  }
  const EngineInput one = Input(false);
  Monitor m(one);
  m.Start(At(one, 0.0, -0.05, 0.0));
  EXPECT_EQ(m.last().mode, ConfigurationOf(Mode::k3b, 1));
  EXPECT_EQ(m.history().blocks, 1);
}

TEST(MonitorTest, GroundImpactTimeIsTheInterpolatedCrossingAndRatesComeAfterContact) {
  const EngineInput in = Input(false);
  Monitor m(in);
  m.Start(At(in, 0.0, 4e-5, -0.4));
  m.Step(1, At(in, 1e-3, 3e-5, -0.4));
  // Crosses zero between 2 and 3 ms: 1e-5 -> -3e-5 puts the zero at 2.25 ms.
  m.Step(2, At(in, 2e-3, 1e-5, -0.4));
  m.Step(3, At(in, 3e-3, -3e-5, -0.41));  // crossed (the impulse may be in this step or next)
  EXPECT_TRUE(m.history().events.empty());
  m.Step(4, At(in, 4e-3, -6e-5, -0.36));  // the engine applied the impulse by now
  m.Finish();
  ASSERT_EQ(m.history().events.size(), 1u);
  const Event& e = m.history().events[0];
  EXPECT_EQ(e.kind, "ground_impact");
  EXPECT_NEAR(e.t_s, 2.25e-3, 1e-12);
  EXPECT_EQ(ModeOfConfiguration(e.mode_before), Mode::k3a);
  EXPECT_EQ(ModeOfConfiguration(e.mode_after), Mode::k3b);
  EXPECT_DOUBLE_EQ(e.omega_before_radps[0], -0.4);  // the step before the crossing
  EXPECT_DOUBLE_EQ(e.omega_after_radps[0], -0.36);
  EXPECT_EQ(m.Summary()["impacts"]["ground"], 1);
}

TEST(MonitorTest, InterfaceImpactWhenBlockTwoLandsOnBlockOne) {
  const EngineInput in = Input(true);
  Monitor m(in);
  // Block 1 flat (mode 4a), block 2 rocking back onto it.
  m.Start(At(in, 0.0, 0.0, 0.0, 2e-4, -0.5));
  m.Step(1, At(in, 1e-3, 0.0, 0.0, 1e-4, -0.5));
  m.Step(2, At(in, 2e-3, 0.0, 0.0, -1e-4, -0.5));  // crossing at 1.5 ms
  m.Step(3, At(in, 3e-3, 0.0, 0.0, -3e-4, -0.4));
  m.Finish();
  ASSERT_EQ(m.history().events.size(), 1u);
  EXPECT_EQ(m.history().events[0].kind, "interface_impact");
  EXPECT_NEAR(m.history().events[0].t_s, 1.5e-3, 1e-12);
  EXPECT_EQ(ModeOfConfiguration(m.history().events[0].mode_before), Mode::k4a);
  EXPECT_EQ(ModeOfConfiguration(m.history().events[0].mode_after), Mode::k4b);
}

TEST(MonitorTest, InitiationAndRestAreModeChanges) {
  const EngineInput in = Input(false);
  Monitor m(in);
  m.Start(At(in, 0.0, 0.0, 0.0));
  m.Step(1, At(in, 1e-3, 0.0, 0.0));
  m.Step(2, At(in, 2e-3, -2e-5, -0.02));  // lifts off its left corner
  m.Finish();
  ASSERT_EQ(m.history().events.size(), 1u);
  EXPECT_EQ(m.history().events[0].kind, "initiation");
  EXPECT_EQ(ModeOfConfiguration(m.history().events[0].mode_after), Mode::k3b);
  EXPECT_EQ(m.Summary()["initiations"], 1);
}

TEST(MonitorTest, SamplesAtTheStepNearestEachOutputTime) {
  // dt = 1 ms, output every 2.4 ms: the steps nearest 0, 2.4, 4.8, 7.2, 9.6 ms.
  const EngineInput in = Input(false, 1e-3, 2.4e-3);
  Monitor m(in);
  m.Start(At(in, 0.0, 0.0, 0.0));
  for (int n = 1; n <= 10; ++n) m.Step(n, At(in, n * 1e-3, 0.0, 0.0));
  m.Finish();
  std::vector<double> t;
  for (const Sample& s : m.history().samples) t.push_back(s.t_s);
  ASSERT_EQ(t.size(), 5u);
  EXPECT_DOUBLE_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 2e-3);
  EXPECT_DOUBLE_EQ(t[2], 5e-3);
  EXPECT_DOUBLE_EQ(t[3], 7e-3);
  EXPECT_DOUBLE_EQ(t[4], 10e-3);
  // The last state is always a sample.
  Monitor m2(in);
  m2.Start(At(in, 0.0, 0.0, 0.0));
  m2.Step(1, At(in, 1e-3, 0.0, 0.0));
  m2.Finish();
  EXPECT_DOUBLE_EQ(m2.history().samples.back().t_s, 1e-3);
}

TEST(MonitorTest, MeasuresSlipUpliftAndPenetration) {
  const EngineInput in = Input(true);
  {
    // Block 1 slides 2 mm to the right on the ground, block 2 riding along.
    Monitor m(in);
    m.Start(At(in, 0.0, 0.0, 0.0));
    for (int n = 1; n <= 20; ++n) {
      StepReadout r = At(in, n * 1e-3, 0.0, 0.0);
      r.blocks[0].x_m += n * 1e-4;
      r.blocks[1].x_m += n * 1e-4;
      m.Step(n, r);
    }
    const auto v = m.Summary()["violations"];
    EXPECT_NEAR(v["slip_ground_m"].get<double>(), 2e-3, 1e-12);
    EXPECT_NEAR(v["drift_ground_max_m"].get<double>(), 2e-3, 1e-12);
    EXPECT_NEAR(v["slip_interface_m"].get<double>(), 0.0, 1e-15);
    EXPECT_TRUE(v["sliding"].get<bool>());  // 2 mm > 1e-3 of the 1.25 m width
    EXPECT_FALSE(v["uplift"].get<bool>());
  }
  {
    // The whole stack jumps 1 mm for 5 steps, then block 2 sinks 0.2 mm into block 1.
    Monitor m(in);
    m.Start(At(in, 0.0, 0.0, 0.0));
    for (int n = 1; n <= 10; ++n) {
      StepReadout r = At(in, n * 1e-3, 0.0, 0.0);
      if (n <= 5) {
        r.blocks[0].y_m += 1e-3;
        r.blocks[1].y_m += 1e-3;
      } else {
        r.blocks[1].y_m -= 2e-4;
      }
      m.Step(n, r);
    }
    const auto v = m.Summary()["violations"];
    EXPECT_EQ(v["uplift_ground_episodes"], 1);
    EXPECT_NEAR(v["uplift_ground_max_m"].get<double>(), 1e-3, 1e-12);
    EXPECT_NEAR(v["uplift_ground_s"].get<double>(), 5e-3, 1e-12);
    EXPECT_NEAR(v["penetration_interface_max_m"].get<double>(), 2e-4, 1e-12);
    EXPECT_TRUE(v["uplift"].get<bool>());
    EXPECT_TRUE(v["penetration"].get<bool>());  // 0.2 mm > 0.1 mm
  }
}

TEST(MonitorTest, EnergyGrowthWithoutInputIsABlowUp) {
  const EngineInput in = Input(false);
  Monitor m(in);
  m.Start(At(in, 0.0, 0.0, 0.0));
  bool go = true;
  int n = 1;
  // Spin the flat block faster and faster with no base input.
  for (; go && n < 100; ++n) go = m.Step(n, At(in, n * 1e-3, 0.0, 0.0 + 0.2 * n));
  EXPECT_FALSE(go);
  EXPECT_EQ(m.status(), RunStatus::kBlowUp);
  const auto s = m.Summary();
  EXPECT_TRUE(s["violations"]["blow_up"].get<bool>());
  EXPECT_TRUE(s["violations"]["energy_growth"].get<bool>());
  EXPECT_GT(s["violations"]["energy_gain_rel"].get<double>(), 1.0);
  // With base input the same growth is not counted.
  Monitor m2(in);
  m2.Start(At(in, 0.0, 0.0, 0.0));
  for (int k = 1; k < 50; ++k) {
    StepReadout r = At(in, k * 1e-3, 0.0, 0.0 + 0.2 * k);
    r.base_accelerating = true;
    EXPECT_TRUE(m2.Step(k, r));
  }
  EXPECT_EQ(m2.Summary()["violations"]["energy_gain_max_j"].get<double>(), 0.0);
}

TEST(MonitorTest, NonFiniteStateStopsTheRunWithoutThrowing) {
  const EngineInput in = Input(true);
  Monitor m(in);
  m.Start(At(in, 0.0, 0.01, 0.0, 0.01, 0.0));
  EXPECT_TRUE(m.Step(1, At(in, 1e-3, 0.01, 0.0, 0.01, 0.0)));
  StepReadout r = At(in, 2e-3, 0.01, 0.0, 0.01, 0.0);
  r.blocks[1].w_radps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(m.Step(2, r));
  EXPECT_FALSE(m.Step(3, At(in, 3e-3, 0.01, 0.0, 0.01, 0.0)));  // stopped: no more steps
  m.Finish();
  EXPECT_EQ(m.status(), RunStatus::kNonFinite);
  // The NaN state is not a sample: the history ends at the last finite state, with an event.
  ASSERT_EQ(m.history().samples.size(), 2u);
  EXPECT_EQ(m.history().samples.back().t_s, 1e-3);
  ASSERT_FALSE(m.history().events.empty());
  EXPECT_EQ(m.history().events.back().kind, "non_finite");
  EXPECT_EQ(m.history().events.back().t_s, 1e-3);
  const nlohmann::json s = m.Summary();
  EXPECT_EQ(s["non_finite"]["quantity"], "omega2");
  EXPECT_EQ(s["non_finite"]["value"], "NaN");
  EXPECT_EQ(s["non_finite"]["t_s"].get<double>(), 2e-3);
  EXPECT_EQ(s["non_finite"]["last_finite_t_s"].get<double>(), 1e-3);
  EXPECT_EQ(s["end_t_s"].get<double>(), 1e-3);
  EXPECT_EQ(s["status_detail"].get<std::string>().rfind("omega2 is NaN at t = 0.002 s (step 2)", 0),
            0u)
      << s["status_detail"];
  EXPECT_TRUE(s["violations"]["blow_up"].get<bool>());
  EXPECT_EQ(m.Outcome().status, RunStatus::kNonFinite);
}

// Finite poses and velocities whose energy overflows (a speed of 1e160 m/s) are not a result
// either; nor is a step the engine itself reports it could not take (ODE, see ode_world.h).
TEST(MonitorTest, AnEnergyThatOverflowsOrAnEngineFaultStopsTheRun) {
  const EngineInput in = Input(false);
  {
    Monitor m(in);
    m.Start(At(in, 0.0, 0.01, 0.0));
    StepReadout r = At(in, 1e-3, 0.01, 0.0);
    r.blocks[0].vx_mps = 1e160;
    EXPECT_FALSE(m.Step(1, r));
    m.Finish();
    EXPECT_EQ(m.status(), RunStatus::kNonFinite);
    EXPECT_EQ(m.Summary()["non_finite"]["quantity"], "energy");
    EXPECT_EQ(m.Summary()["non_finite"]["value"], "+inf");
    EXPECT_EQ(m.history().samples.size(), 1u);
  }
  {
    Monitor m(in);
    m.Start(At(in, 0.0, 0.01, 0.0));
    StepReadout r = At(in, 1e-3, 0.01, 0.0);
    r.engine_fault = "the step was not taken";
    EXPECT_FALSE(m.Step(1, r));
    EXPECT_EQ(m.status(), RunStatus::kNonFinite);
    const std::string detail = m.Summary()["status_detail"].get<std::string>();
    EXPECT_NE(detail.find("the step was not taken"), std::string::npos) << detail;
  }
}

// Overturning is the reference's definition: |theta| reaches model.overturn_angle (no slack), at
// the crossing interpolated inside the step, on either side.
TEST(MonitorTest, OverturnIsTheInterpolatedCrossingOfTheModelAngle) {
  const double half_pi = std::numbers::pi / 2;
  for (const double side : {1.0, -1.0}) {
    SCOPED_TRACE(side);
    EngineInput in = Input(false);
    in.overturn_rad = half_pi;
    Monitor m(in);
    m.Start(At(in, 0.0, side * 1.0, side * 2.0));
    EXPECT_TRUE(m.Step(1, At(in, 1e-3, side * 1.5, side * 2.0)));
    // 0.005 rad short of the overturn angle is not overturned (the old 0.01 rad slack said it was).
    EXPECT_TRUE(m.Step(2, At(in, 2e-3, side * (half_pi - 0.005), side * 2.0)));
    // Crossed a quarter into the step: overturned at 2.25 ms, not at the step's end.
    EXPECT_FALSE(m.Step(3, At(in, 3e-3, side * (half_pi + 0.015), side * 2.0)));
    m.Finish();
    EXPECT_EQ(m.status(), RunStatus::kOverturned);
    const auto s = m.Summary();
    EXPECT_EQ(s["overturn"]["block"], 1);
    EXPECT_NEAR(s["overturn"]["t_s"].get<double>(), 2.25e-3, 1e-15);
    EXPECT_FALSE(s["monitor"].contains("overturn_slack_rad"));
    ASSERT_FALSE(m.history().events.empty());
    const Event& e = m.history().events.back();
    EXPECT_EQ(e.kind, "overturn");
    EXPECT_NEAR(e.t_s, 2.25e-3, 1e-15);
    // The last sample is the state at the step's end.
    EXPECT_EQ(m.history().samples.back().t_s, 3e-3);
  }
}

TEST(MonitorTest, OverturnOfTwoBlocksInOneStepIsTheFirstCrossing) {
  const double half_pi = std::numbers::pi / 2;
  EngineInput in = Input(true);
  in.overturn_rad = half_pi;
  Monitor m(in);
  m.Start(At(in, 0.0, 1.2, 2.0, 1.3, 2.0));
  EXPECT_TRUE(m.Step(1, At(in, 1e-3, half_pi - 0.01, 2.0, half_pi - 0.002, 2.0)));
  // Block 1 crosses 0.8 into the step, block 2 0.1 into it: block 2 overturned, at 1.1 ms.
  EXPECT_FALSE(m.Step(2, At(in, 2e-3, half_pi + 0.0025, 2.0, half_pi + 0.018, 2.0)));
  m.Finish();
  const auto s = m.Summary();
  EXPECT_EQ(s["overturn"]["block"], 2);
  EXPECT_NEAR(s["overturn"]["t_s"].get<double>(), 1.1e-3, 1e-15);
  EXPECT_EQ(m.history().events.back().note, "block 2");
}

// ---------------------------------------------------------------------------------------------
// Three blocks: every per-interface quantity is block k's relative to its support, in the
// support's frame.

// Three drums 0.9 m wide and 0.85 m tall, 2700 kg/m^3, 1 m deep.
EngineInput ThreeDrums(double dt = 1e-3) {
  EngineInput in = Input(false, dt, dt);
  in.blocks.assign(3, BlockDef{0.9, 0.85, 1.0, 0.9 * 0.85 * 2700.0, 2700.0});
  return in;
}

// The readout of an exact pivot-chain state of N blocks.
StepReadout AtN(const EngineInput& in, double t, const std::vector<double>& theta,
                const std::vector<double>& omega) {
  InitialState state;
  for (size_t k = 0; k < theta.size(); ++k) {
    state.theta_rad[k] = theta[k];
    state.omega_radps[k] = omega[k];
  }
  const StackPlacement p = PlaceStack(in.blocks, state);
  StepReadout r(in.block_count());
  r.t_s = t;
  for (int k = 0; k < in.block_count(); ++k) r.blocks[k] = ToReadout(p.blocks[k]);
  return r;
}

TEST(MonitorNBlocks, InfersEveryInterfaceSideOfThreeBlocks) {
  struct Case {
    std::vector<double> theta, omega;
    const char* name;
  };
  // The side of interface k is that of theta_k - theta_(k-1) (its rate when flat): r, l or f.
  const Case cases[] = {
      {{0.1, 0.15, 0.2}, {0, 0, 0}, "rrr"},   {{0.1, 0.1, 0.05}, {0, 0, 0}, "rfl"},
      {{0.0, 0.0, 0.1}, {0, 0, 0}, "ffr"},    {{-0.1, -0.05, -0.05}, {0, 0, 0}, "lrf"},
      {{0.0, 0.0, 0.0}, {0, 0, 0}, "fff"},    {{0.1, 0.1, 0.1}, {0.5, 0.5, 0.5}, "rff"},
      {{0.0, 0.0, 0.0}, {0, 0, -0.5}, "ffl"}, {{0.0, 0.0, 0.0}, {0.5, 0.5, 1.0}, "rfr"},
      {{-0.2, 0.1, -0.1}, {0, 0, 0}, "lrl"},  {{2e-6, 2e-6, 2e-6}, {1e-3, 1e-3, 1e-3}, "fff"},
  };
  const EngineInput in = ThreeDrums();
  for (const Case& c : cases) {
    Monitor m(in);
    m.Start(AtN(in, 0.0, c.theta, c.omega));
    EXPECT_EQ(ConfigurationName(m.last().mode), c.name)
        << c.theta[0] << " " << c.theta[1] << " " << c.theta[2];
    EXPECT_EQ(m.last().theta_rad.size(), 3u);
    EXPECT_NEAR(m.last().theta_rad[2], c.theta[2], 1e-15);
  }
}

TEST(MonitorNBlocks, ImpactOfTheTopBlockOnTheMiddleOne) {
  // Blocks 1 and 2 tilted together at 0.05 rad (interface 2 closed), block 3 rocking back onto
  // block 2: its relative angle 2e-4, 1e-4, -1e-4 rad at 0, 1, 2 ms crosses zero at 1.5 ms.
  const EngineInput in = ThreeDrums();
  const double th = 0.05;
  Monitor m(in);
  m.Start(AtN(in, 0.0, {th, th, th + 2e-4}, {0.0, 0.0, -0.1}));
  EXPECT_EQ(ConfigurationName(m.last().mode), "rfr");
  m.Step(1, AtN(in, 1e-3, {th, th, th + 1e-4}, {0.0, 0.0, -0.1}));
  m.Step(2, AtN(in, 2e-3, {th, th, th - 1e-4}, {0.0, 0.0, -0.1}));
  m.Step(3, AtN(in, 3e-3, {th, th, th - 2e-4}, {0.0, 0.0, -0.08}));
  m.Finish();
  ASSERT_EQ(m.history().events.size(), 1u);
  const Event& e = m.history().events[0];
  EXPECT_EQ(e.kind, "interface3_impact");
  EXPECT_NEAR(e.t_s, 1.5e-3, 1e-12);
  EXPECT_EQ(ConfigurationName(e.mode_before), "rfr");
  EXPECT_EQ(ConfigurationName(e.mode_after), "rfl");
  ASSERT_EQ(e.omega_before_radps.size(), 3u);
  EXPECT_DOUBLE_EQ(e.omega_before_radps[2], -0.1);
  EXPECT_DOUBLE_EQ(e.omega_after_radps[2], -0.08);
  // The energy is every block's: m g y_G + kinetic, of the state before the crossing step.
  InitialState before;
  for (int k = 0; k < 3; ++k) before.theta_rad[k] = th;
  before.theta_rad[2] = th + 1e-4;
  before.omega_radps[2] = -0.1;
  const StackPlacement p = PlaceStack(in.blocks, before);
  double energy = 0.0;
  for (int k = 0; k < 3; ++k) {
    const PlanarPose& q = p.blocks[k];
    const double mass = in.blocks[k].mass_kg, b = 0.45, h = 0.425;
    energy += mass * 9.81 * q.y_m + 0.5 * mass * (q.vx_mps * q.vx_mps + q.vy_mps * q.vy_mps) +
              0.5 * mass * (b * b + h * h) / 3.0 * q.w_radps * q.w_radps;
  }
  EXPECT_NEAR(e.energy_before_j, energy, 1e-12 * energy);
  // Counted at interface 3 (block 3 on block 2) only.
  const RunOutcome o = m.Outcome();
  EXPECT_EQ(o.impacts_at, (std::vector<int>{0, 0, 1}));
  const nlohmann::json s = m.Summary();
  EXPECT_EQ(s["impacts"]["total"], 1);
  EXPECT_EQ(s["impacts"]["ground"], 0);
  EXPECT_EQ(s["impacts"]["interface2"], 0);
  EXPECT_EQ(s["impacts"]["interface3"], 1);
  EXPECT_FALSE(s["impacts"].contains("interface"));
}

TEST(MonitorNBlocks, ImpactsAtTwoInterfacesInOneStepAreBothCounted) {
  // Block 1 tilted at 0.05 on the ground; blocks 2 and 3 each 1e-4 rad to the right of the
  // block below, then 1e-4 rad to its left: both interfaces land at 0.5 ms, each its impact.
  const EngineInput in = ThreeDrums();
  const double th = 0.05;
  Monitor m(in);
  m.Start(AtN(in, 0.0, {th, th + 1e-4, th + 2e-4}, {0.0, -0.2, -0.4}));
  EXPECT_EQ(ConfigurationName(m.last().mode), "rrr");
  m.Step(1, AtN(in, 1e-3, {th, th - 1e-4, th - 2e-4}, {0.0, -0.2, -0.4}));
  m.Step(2, AtN(in, 2e-3, {th, th - 2e-4, th - 4e-4}, {0.0, -0.1, -0.2}));
  m.Finish();
  ASSERT_EQ(m.history().events.size(), 2u);
  EXPECT_EQ(m.history().events[0].kind, "interface2_impact");
  EXPECT_EQ(m.history().events[1].kind, "interface3_impact");
  for (const Event& e : m.history().events) {
    EXPECT_NEAR(e.t_s, 0.5e-3, 1e-12) << e.kind;
    EXPECT_EQ(ConfigurationName(e.mode_before), "rrr") << e.kind;
    EXPECT_EQ(ConfigurationName(e.mode_after), "rll") << e.kind;
  }
  EXPECT_EQ(m.Outcome().impacts_at, (std::vector<int>{0, 1, 1}));
  EXPECT_EQ(m.Summary()["impacts"]["total"], 2);
}

TEST(MonitorNBlocks, SlipUpliftAndPenetrationOfTheTopBlockAreMeasuredOnItsSupport) {
  // The column tilted as one at 0.1 rad. Block 3 is moved along block 2's top face (block 2's
  // own x axis, not the ground's): slip at interface 3 only.
  const EngineInput in = ThreeDrums();
  const std::vector<double> tilt = {0.1, 0.1, 0.1}, still = {0.0, 0.0, 0.0};
  const double phi = -0.1;
  const Vec2 along{std::cos(phi), std::sin(phi)}, normal{-std::sin(phi), std::cos(phi)};
  {
    Monitor m(in);
    m.Start(AtN(in, 0.0, tilt, still));
    for (int n = 1; n <= 20; ++n) {
      StepReadout r = AtN(in, n * 1e-3, tilt, still);
      r.blocks[2].x_m += n * 1e-4 * along.x;
      r.blocks[2].y_m += n * 1e-4 * along.y;
      m.Step(n, r);
    }
    const auto v = m.Summary()["violations"];
    EXPECT_NEAR(v["slip_interface3_m"].get<double>(), 2e-3, 1e-12);
    EXPECT_NEAR(v["drift_interface3_max_m"].get<double>(), 2e-3, 1e-12);
    EXPECT_NEAR(v["slip_interface2_m"].get<double>(), 0.0, 1e-14);
    EXPECT_NEAR(v["slip_ground_m"].get<double>(), 0.0, 1e-14);
    EXPECT_FALSE(v.contains("slip_interface_m"));
    EXPECT_TRUE(v["sliding"].get<bool>());  // 2 mm > 1e-3 of the 0.9 m width
    EXPECT_FALSE(v["uplift"].get<bool>());
    EXPECT_LT(v["penetration_interface3_max_m"].get<double>(), 1e-14);
  }
  {
    // Block 3 lifts 1 mm off block 2 (along block 2's normal) for 5 steps, then sinks 0.2 mm.
    Monitor m(in);
    m.Start(AtN(in, 0.0, tilt, still));
    for (int n = 1; n <= 10; ++n) {
      StepReadout r = AtN(in, n * 1e-3, tilt, still);
      const double d = n <= 5 ? 1e-3 : -2e-4;
      r.blocks[2].x_m += d * normal.x;
      r.blocks[2].y_m += d * normal.y;
      m.Step(n, r);
    }
    const auto v = m.Summary()["violations"];
    EXPECT_EQ(v["uplift_interface3_episodes"], 1);
    EXPECT_NEAR(v["uplift_interface3_max_m"].get<double>(), 1e-3, 1e-12);
    EXPECT_NEAR(v["uplift_interface3_s"].get<double>(), 5e-3, 1e-12);
    EXPECT_NEAR(v["penetration_interface3_max_m"].get<double>(), 2e-4, 1e-12);
    EXPECT_EQ(v["uplift_interface2_episodes"], 0);
    EXPECT_EQ(v["uplift_ground_episodes"], 0);
    EXPECT_TRUE(v["uplift"].get<bool>());
    EXPECT_TRUE(v["penetration"].get<bool>());
  }
}

TEST(MonitorNBlocks, TheFirstBlockToReachTheOverturnAngleOverturns) {
  const double half_pi = std::numbers::pi / 2;
  EngineInput in = ThreeDrums();
  in.overturn_rad = half_pi;
  Monitor m(in);
  m.Start(AtN(in, 0.0, {1.2, 1.2, 1.3}, {2.0, 2.0, 2.0}));
  EXPECT_TRUE(
      m.Step(1, AtN(in, 1e-3, {half_pi - 0.01, half_pi - 0.01, half_pi - 0.002}, {2.0, 2.0, 2.0})));
  // Blocks 1 and 2 cross 0.8 into the step, block 3 0.1 into it: block 3, at 1.1 ms.
  EXPECT_FALSE(m.Step(
      2, AtN(in, 2e-3, {half_pi + 0.0025, half_pi + 0.0025, half_pi + 0.018}, {2.0, 2.0, 2.0})));
  m.Finish();
  const auto s = m.Summary();
  EXPECT_EQ(s["overturn"]["block"], 3);
  EXPECT_NEAR(s["overturn"]["t_s"].get<double>(), 1.1e-3, 1e-15);
  EXPECT_EQ(m.Outcome().overturned_block, 3);
  EXPECT_EQ(m.history().events.back().note, "block 3");
}

TEST(MonitorNBlocks, SummaryKeysGoOnByBlockAndInterface) {
  const EngineInput in = ThreeDrums();
  Monitor m(in);
  m.Start(AtN(in, 0.0, {0.02, 0.03, 0.05}, {0.0, 0.0, 0.0}));
  m.Step(1, AtN(in, 1e-3, {0.02, 0.03, 0.06}, {0.0, 0.0, 1.0}));
  m.Finish();
  const nlohmann::json s = m.Summary();
  EXPECT_NEAR(s["peaks"]["theta3"]["abs_rad"].get<double>(), 0.06, 1e-15);
  EXPECT_EQ(s["peaks"]["theta3"]["t_s"].get<double>(), 1e-3);
  EXPECT_NEAR(s["final"]["theta3_rad"].get<double>(), 0.06, 1e-15);
  EXPECT_NEAR(s["final"]["omega3_radps"].get<double>(), 1.0, 1e-15);
  EXPECT_EQ(s["final"]["mode"], "rrr");
  EXPECT_EQ(s["violations"]["significant_displacement_m"].size(), 3u);
  for (const char* k : {"slip_interface2_m", "uplift_interface3_s", "penetration_ground_max_m",
                        "drift_interface2_max_m"}) {
    EXPECT_TRUE(s["violations"].contains(k)) << k;
  }
  const RunOutcome o = m.Outcome();
  EXPECT_EQ(o.blocks(), 3);
  EXPECT_EQ(m.history().blocks, 3);
  for (const Sample& x : m.history().samples) EXPECT_EQ(x.blocks(), 3);
}

TEST(MonitorNBlocks, AReadoutOfAnotherNumberOfBodiesIsRefused) {
  const EngineInput in = ThreeDrums();
  Monitor m(in);
  EXPECT_THROW(m.Start(StepReadout(2)), std::invalid_argument);
  m.Start(AtN(in, 0.0, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}));
  EXPECT_THROW(m.Step(1, StepReadout(4)), std::invalid_argument);
}

// Slip and lift (issue 24) as the reference defines them (docs/sliding.md): u_k the slip of
// block k's base corner on the side of its relative tilt along its support's top face, from
// where it stood at rest; z_k the height of its lowest base corner above that face's line. The
// pivot chain's states have none; block 1 moved 1 cm left on the ground and block 2 moved 3 cm
// along block 1's tilted face and 2 mm off it have exactly those; the history carries them
// only with EngineInput::slip_and_lift.
TEST(MonitorTest, SlipAndLiftAreTheReferencesOnTheSupportsFace) {
  for (const bool tracked : {false, true}) {
    EngineInput in = Input(true);
    in.slip_and_lift = tracked;
    Monitor m(in);
    const double th1 = -0.1, th2 = -0.15;  // both tilted left, block 2 left on block 1
    m.Start(At(in, 0.0, th1, 0.0, th2, 0.0));
    EXPECT_EQ(m.history().slip_and_lift, tracked);
    if (!tracked) {
      EXPECT_TRUE(m.last().u_m.empty() && m.last().z_m.empty());
      continue;
    }
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(m.last().u_m[k], 0.0, 1e-15) << k;
      EXPECT_NEAR(m.last().z_m[k], 0.0, 1e-15) << k;
    }
    StepReadout r = At(in, 1e-3, th1, 0.0, th2, 0.0);
    for (BodyReadout& b : r.blocks) b.x_m -= 0.01;
    // Block 1's face: tangent (cos phi1, sin phi1), normal (-sin phi1, cos phi1), phi1 = -th1.
    const double c1 = std::cos(-th1), s1 = std::sin(-th1);
    r.blocks[1].x_m += 0.03 * c1 - 0.002 * s1;
    r.blocks[1].y_m += 0.03 * s1 + 0.002 * c1;
    m.Step(1, r);
    EXPECT_NEAR(m.last().u_m[0], -0.01, 1e-14);
    EXPECT_NEAR(m.last().z_m[0], 0.0, 1e-14);
    EXPECT_NEAR(m.last().u_m[1], 0.03, 1e-14);
    EXPECT_NEAR(m.last().z_m[1], 0.002, 1e-14);
    m.Finish();
    ASSERT_EQ(m.history().samples.size(), 2u);
    EXPECT_EQ(m.history().samples[1].u_m, m.last().u_m);
  }
}

}  // namespace
}  // namespace rockbench

namespace rockbench {
namespace {

// A cylinder's engine that refuses its step (ODE before an orientation update it would abort
// on) says why: the run ends non_finite with the engine's words, not only "not finite".
TEST(CylinderMonitorTest, AnEnginesRefusedStepEndsTheRunWithItsReason) {
  const Scene scene = ParseScene(
      "[[block]]\nshape = \"cylinder\"\ndiameter = 0.5\nheight = 1.5\ndensity = 2500\n"
      "[initial]\ntilt = [0.1]\n[run]\nduration = 0.01\noutput_interval = 0.001\n",
      "c.toml", {});
  const EngineInput in =
      MakeEngineInput(scene, GroundMotion{}, "test", 1e-3, DriveKind::kInertial, 0.0);
  CylinderMonitor monitor(in);
  CylinderPose pose = CylinderStartPose(in);
  monitor.Start(pose);
  EXPECT_TRUE(monitor.Step(1, pose));
  pose.engine_fault = "the engine's orientation update would overflow: the step was not taken";
  EXPECT_FALSE(monitor.Step(2, pose));
  EXPECT_EQ(monitor.Outcome().status, RunStatus::kNonFinite);
  const std::string detail = monitor.Summary()["status_detail"].get<std::string>();
  EXPECT_EQ(detail.find(pose.engine_fault), 0u) << detail;
  EXPECT_NE(detail.find("t = 0.002"), std::string::npos) << detail;
}

}  // namespace
}  // namespace rockbench
