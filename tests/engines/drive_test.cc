// What every engine is driven with (engines/common/engine_input.h), tested on its own, without
// any engine: the base motion on the step grid, the kinematic drive's ground path and its
// report, the initial poses of the pivot chain, and the promise that the animations draw the
// ground along the same path (renders/drawn_motion.h IntegrateBaseDisplacement).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engines/common/engine_input.h"
#include "motion/ground_displacement.h"
#include "renders/drawn_motion.h"
#include "scene/stack_pose.h"
#include "tests/common/initial_state.h"
#include "tests/common/one_block_scene.h"

namespace rockbench {
namespace {

Scene HarmonicScene(double duration_s) {
  Scene s = testing_util::OneBlockScene();
  s.run.duration_s = duration_s;
  MotionDef h;
  h.key = "base.horizontal";
  h.kind = MotionKind::kHarmonic;
  h.amplitude_g = 0.2;
  h.frequency_hz = 3.0;
  h.duration_s = 1.0;
  s.horizontal = h;
  return s;
}

// Second difference of u divided by dt^2 at step n (u_{-1} from the velocity before step 0).
double SecondDifference(const std::vector<double>& u, double v_before, double dt, size_t n) {
  const double prev = n == 0 ? u[0] - v_before * dt : u[n - 1];
  return (u[n + 1] - 2.0 * u[n] + prev) / (dt * dt);
}

TEST(EngineDrive, SamplesTheBaseMotionAtTheStepStarts) {
  Scene s = testing_util::OneBlockScene();
  s.run.duration_s = 0.0105;  // not a multiple of dt: 11 steps
  GroundMotion m;
  m.set_horizontal(MotionComponent::FromSamples({0.0, 1.0}, 0.01, 0.0, "ramp"));
  const EngineInput in = MakeEngineInput(s, m, "test", 1e-3, DriveKind::kInertial, 0.0);
  EXPECT_EQ(in.steps, 11);
  ASSERT_EQ(in.drive.ax_mps2.size(), 11u);
  ASSERT_EQ(in.drive.ay_mps2.size(), 11u);
  for (size_t n = 0; n < 11; ++n) {
    EXPECT_NEAR(in.drive.ax_mps2[n], m.xg_mps2(n * 1e-3), 1e-15);
    EXPECT_EQ(in.drive.ay_mps2[n], 0.0);
  }
  EXPECT_TRUE(in.drive.ux_m.empty());  // inertial drive: no ground displacement
  EXPECT_DOUBLE_EQ(in.motion_end_s, 0.01);
  // No base motion: nothing stored, the drive reads zeros.
  const EngineInput still = MakeEngineInput(testing_util::OneBlockScene(), GroundMotion(), "test",
                                            1e-4, DriveKind::kInertial, 0.0);
  EXPECT_TRUE(still.drive.ax_mps2.empty());
  EXPECT_EQ(still.steps, 10000);
}

TEST(EngineDrive, RefusesATimeStepOfTooManyStepsNamingTheEnginesKey) {
  Scene s = testing_util::OneBlockScene();
  s.path = "scenes/x.toml";
  for (const double dt : {0.0, -1e-3, 1e-12}) {
    try {
      MakeEngineInput(s, GroundMotion(), "test", dt, DriveKind::kInertial, 0.0);
      ADD_FAILURE() << "accepted time step " << dt;
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("scenes/x.toml: test.time_step: expected"), std::string::npos) << what;
    }
  }
}

TEST(EngineDrive, KinematicDriveFillsTheGroundPathAndItsReport) {
  const Scene s = HarmonicScene(2.0);
  const GroundMotion m = GroundMotion::FromScene(s);
  const EngineInput in = MakeEngineInput(s, m, "test", 1e-3, DriveKind::kKinematic, 0.0);
  ASSERT_EQ(in.drive.ux_m.size(), 2001u);
  ASSERT_EQ(in.drive.uy_m.size(), 2001u);
  EXPECT_EQ(*std::max_element(in.drive.uy_m.begin(), in.drive.uy_m.end()), 0.0);
  EXPECT_GT(in.drive.raw_peak_x_m, 0.0);
  EXPECT_GT(in.drive.peak_x_m, 0.0);
  EXPECT_GT(in.drive.correction_max_x_mps2, 0.0);
  EXPECT_LT(in.drive.correction_max_x_mps2, 0.05 * 0.2 * kStandardGravity_mps2);
  // The report is the largest |second difference - record| over the run.
  double worst = 0.0;
  for (size_t k = 0; k < 2000; ++k) {
    worst = std::max(worst, std::abs(SecondDifference(in.drive.ux_m, in.drive.ux0_mps, 1e-3, k) -
                                     in.drive.ax_mps2[k]));
  }
  EXPECT_NEAR(in.drive.correction_max_x_mps2, worst, 1e-9);
}

TEST(EngineDrive, TheKinematicPathIsTheScenesGroundPath) {
  // The drive's path is scene/ground_displacement.h's, bit for bit, with and without the
  // high-pass: one definition of the ground's displacement.
  const Scene s = HarmonicScene(3.0);
  const GroundMotion m = GroundMotion::FromScene(s);
  for (const double fc : {0.0, 0.3}) {
    const EngineInput in = MakeEngineInput(s, m, "test", 5e-4, DriveKind::kKinematic, fc);
    std::vector<double> ax, ay;
    SampleGroundAcceleration(m, 5e-4, static_cast<size_t>(in.steps), &ax, &ay);
    const GroundPath px = IntegrateGroundPath(ax, 5e-4, fc);
    EXPECT_EQ(in.drive.ux_m, px.u_m) << "fc " << fc;
    EXPECT_EQ(in.drive.ux0_mps, px.velocity_before_mps) << "fc " << fc;
    EXPECT_EQ(in.drive.raw_peak_x_m, px.raw_peak_m) << "fc " << fc;
  }
}

TEST(EngineDrive, TheAnimationDrawsTheGroundTheKinematicEngineWasDrivenWith) {
  // A scene whose engine runs the kinematic drive: the renders take its step and high-pass from
  // the scene (BaseIntegrationFor) and draw the ground where the engine put it, at every step.
  Scene s = HarmonicScene(3.0);
  SetEngineSetting(s, "bullet", "drive", std::string("kinematic"));
  SetEngineSetting(s, "bullet", "time_step", 5e-4);
  SetEngineSetting(s, "bullet", "kinematic_highpass_hz", 0.3);
  const GroundMotion m = GroundMotion::FromScene(s);
  const EngineInput in = MakeEngineInput(s, m, "bullet", 5e-4, DriveKind::kKinematic, 0.3);
  const renders::BaseIntegrationConfig config = renders::BaseIntegrationFor(s);
  EXPECT_EQ(config.dt_s, 5e-4);
  EXPECT_EQ(config.highpass_hz, 0.3);
  // Drawn up to an earlier time (a run that overturned): the same path, the filter still runs
  // over the whole run.
  for (const double t_end_s : {3.0, 1.7}) {
    const renders::BaseDisplacement base = renders::IntegrateBaseDisplacement(m, t_end_s, config);
    for (size_t n = 0; n * 5e-4 <= t_end_s; n += 97) {
      // At t = n dt the interpolation weight is 0 or within rounding of it: 1e-15 m.
      EXPECT_NEAR(base.At(static_cast<double>(n) * 5e-4).x, in.drive.ux_m[n], 1e-15) << n;
    }
  }
}

TEST(EngineDrive, InitialPosesAreThePivotChains) {
  // The poses an engine starts from are scene/stack_pose.h's, for the input's blocks and state.
  Scene s = testing_util::OneBlockScene();
  s.blocks.resize(1);
  s.blocks.push_back(BlockDef{0.6, 2.0, 1.0, 1000.0, 0.0});
  s.initial = testing_util::Initial(0.1, 0.25, 0.0, 0.5);
  const EngineInput in =
      MakeEngineInput(s, GroundMotion(), "test", 1e-3, DriveKind::kInertial, 0.0);
  const StackPlacement a = PlaceStack(s, in.initial);
  const StackPlacement c = PlaceStack(in.blocks, in.initial);
  ASSERT_EQ(a.blocks.size(), 2u);
  ASSERT_EQ(c.blocks.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(a.blocks[k].x_m, c.blocks[k].x_m);
    EXPECT_EQ(a.blocks[k].y_m, c.blocks[k].y_m);
    EXPECT_EQ(a.blocks[k].vx_mps, c.blocks[k].vx_mps);
  }
  EXPECT_EQ(a.sides[1], 1);
  EXPECT_EQ(c.sides[1], 1);
}

TEST(EngineDrive, TheInputCarriesEveryBlockOfAnNBlockStack) {
  // Six drums: the input holds the scene's blocks and state, bottom first.
  Scene s = testing_util::OneBlockScene();
  s.blocks.assign(6, BlockDef{0.9, 0.85, 0.9, 0.9 * 0.85 * 0.9 * 2700.0, 2700.0});
  for (int k = 0; k < 6; ++k) s.initial.theta_rad[k] = 0.05;
  s.initial.omega_radps[5] = -0.1;
  const EngineInput in =
      MakeEngineInput(s, GroundMotion(), "test", 1e-3, DriveKind::kInertial, 0.0);
  ASSERT_EQ(in.block_count(), 6);
  EXPECT_EQ(in.blocks[5].mass_kg, s.blocks[5].mass_kg);
  EXPECT_EQ(in.initial.theta_rad[5], 0.05);
  EXPECT_EQ(in.initial.omega_radps[5], -0.1);
}

}  // namespace
}  // namespace rockbench
