// The file format between rockbench and the float helper: bit-exact round trips, and clear
// errors for truncated, foreign or stale files.
#include "engines/bullet/protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tests/common/initial_state.h"
#include "tests/common/sample.h"

namespace rockbench::bullet {
namespace {

using testing_util::MakeSample;

BulletInput SomeInput() {
  BulletInput in;
  in.blocks = {{1.25, 1.25, 0.7, 3906.25, 2500.0}, {1.0, 2.5, 1.1, 6250.0, 0.0}};
  in.initial = testing_util::Initial(0.1, 0.2, -0.3, 1.0 / 3.0);
  in.run = {20.0, 0.01, 9.80665};
  in.time_step_s = 1.0 / 60.0;
  in.config.solver_iterations = 77;
  in.config.precision = BulletPrecision::kFloat;
  in.drive_kind = DriveKind::kKinematic;
  in.config.erp = 0.1;
  in.config.erp2 = 0.7;
  in.config.split_impulse = false;
  in.config.split_impulse_threshold = 0.0;
  in.config.restitution = 0.05;
  in.config.friction = 2.0;
  in.config.rolling_friction = 0.001;
  in.config.restitution_velocity_threshold = 0.1;
  in.config.margin_m = 0.002;
  in.config.ground_depth_m = 3.0;
  in.kinematic_highpass_hz = 0.05;
  in.overturn_rad = 1.2;
  in.steps = 1200;
  in.motion_end_s = 19.9;
  in.stop_at_rest_after_s = 7.25;
  for (int k = 0; k < 1200; ++k) {
    in.drive.ax_mps2.push_back(std::sin(0.1 * k) / 7.0);
    in.drive.ay_mps2.push_back(std::cos(0.3 * k) / 3.0);
  }
  for (int k = 0; k <= 1200; ++k) {
    in.drive.ux_m.push_back(1e-3 * k / 9.0);
    in.drive.uy_m.push_back(-1e-4 * k / 11.0);
  }
  in.drive.ux0_mps = 1e-7 / 3.0;
  in.drive.uy0_mps = -2e-7;
  in.drive.correction_max_x_mps2 = 0.123;
  in.drive.correction_max_y_mps2 = 0.456;
  in.drive.raw_peak_x_m = 1.5;
  in.drive.raw_peak_y_m = 0.25;
  in.drive.peak_x_m = 0.3;
  in.drive.peak_y_m = 0.05;
  return in;
}

TEST(ProtocolTest, InputRoundTripIsBitExact) {
  const BulletInput a = SomeInput();
  const std::string bytes = SerializeInput(a);
  const BulletInput b = ParseInput(bytes);
  EXPECT_EQ(SerializeInput(b), bytes);  // every field, every bit
  EXPECT_EQ(b.blocks[1].depth_m, 1.1);
  EXPECT_EQ(b.initial.omega_radps[1], 1.0 / 3.0);
  EXPECT_EQ(b.config.precision, BulletPrecision::kFloat);
  EXPECT_EQ(b.drive_kind, DriveKind::kKinematic);
  EXPECT_EQ(b.config.solver_iterations, 77);
  EXPECT_EQ(b.drive.ax_mps2, a.drive.ax_mps2);
  EXPECT_EQ(b.drive.uy_m, a.drive.uy_m);
  EXPECT_EQ(b.steps, 1200);
  // A single block and empty drive arrays survive too.
  BulletInput one;
  one.blocks = {{1.0, 4.0, 1.0, 1e4, 0.0}};
  const BulletInput c = ParseInput(SerializeInput(one));
  EXPECT_EQ(c.block_count(), 1);
  EXPECT_TRUE(c.drive.ax_mps2.empty());
}

TEST(ProtocolTest, AnNBlockInputCarriesEveryBlockAngleAndRate) {
  BulletInput in = SomeInput();
  in.blocks.clear();
  for (int k = 0; k < 5; ++k) {
    in.blocks.push_back(BlockDef{0.9 - 0.01 * k, 0.85, 0.9, 2000.0 + k / 3.0, 2700.0});
    in.initial.theta_rad[k] = 0.05 + k / 7.0;
    in.initial.omega_radps[k] = -k / 11.0;
  }
  const std::string bytes = SerializeInput(in);
  const BulletInput b = ParseInput(bytes);
  EXPECT_EQ(SerializeInput(b), bytes);
  ASSERT_EQ(b.block_count(), 5);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(b.blocks[k].width_m, in.blocks[k].width_m);
    EXPECT_EQ(b.blocks[k].mass_kg, in.blocks[k].mass_kg);
    EXPECT_EQ(b.initial.theta_rad[k], in.initial.theta_rad[k]);
    EXPECT_EQ(b.initial.omega_radps[k], in.initial.omega_radps[k]);
  }
  EXPECT_EQ(b.initial.theta_rad[5], 0.0);
  // A block count out of range is refused.
  std::string bad = bytes;
  const std::int32_t none = 0;
  std::memcpy(&bad[12], &none, sizeof none);  // after the magic (8) and the version (4)
  EXPECT_THROW(ParseInput(bad), std::runtime_error);
}

TEST(ProtocolTest, OutputRoundTripIsBitExact) {
  EngineResult a;
  a.history.blocks = 2;
  a.history.samples.push_back(MakeSample({0.0, 0.1, 0.2, 0.3, 0.4, Mode::k1a}));
  a.history.samples.push_back(MakeSample({1e-3, -1.0 / 3.0, 2.0 / 7.0, 0.5, -0.5, Mode::k4b}));
  Event e(2);
  e.t_s = 0.6983;
  e.kind = "ground_impact";
  e.mode_before = ConfigurationOf(Mode::k3a, 2);
  e.mode_after = ConfigurationOf(Mode::k3b, 2);
  e.omega_before_radps[0] = -0.3995;
  e.omega_after_radps[0] = -0.3642;
  e.energy_before_j = 1.0 / 3.0;
  e.note = "a note";
  a.history.events.push_back(e);
  a.summary = {{"status", "completed"}, {"violations", {{"slip_ground_m", 1e-7}}}};
  a.outcome = RunOutcome(2);
  a.outcome.status = RunStatus::kOverturned;
  a.outcome.overturned_block = 2;
  a.outcome.overturn_t_s = 3.25;
  a.outcome.peak_theta_rad[1] = 1.5;
  a.outcome.impacts_at[1] = 4;
  a.outcome.violations = {"uplift", "energy_growth"};
  a.wall_s = 0.125;
  const EngineResult b = ParseOutput(SerializeOutput(a));
  EXPECT_EQ(SerializeOutput(b), SerializeOutput(a));
  ASSERT_EQ(b.history.samples.size(), 2u);
  EXPECT_EQ(b.history.samples[1].theta_rad[0], -1.0 / 3.0);
  EXPECT_EQ(ModeOfConfiguration(b.history.samples[1].mode), Mode::k4b);
  ASSERT_EQ(b.history.events.size(), 1u);
  EXPECT_EQ(b.history.events[0].kind, "ground_impact");
  EXPECT_EQ(b.history.events[0].note, "a note");
  EXPECT_EQ(b.summary["violations"]["slip_ground_m"], 1e-7);
  // The typed outcome travels bit-exact.
  EXPECT_EQ(b.outcome.status, RunStatus::kOverturned);
  EXPECT_EQ(b.outcome.overturned_block, 2);
  EXPECT_EQ(b.outcome.overturn_t_s, 3.25);
  EXPECT_EQ(b.outcome.peak_theta_rad[1], 1.5);
  EXPECT_EQ(b.outcome.impacts_interface(), 4);
  EXPECT_EQ(b.outcome.violations, a.outcome.violations);
  EXPECT_EQ(b.wall_s, 0.125);
}

// Issue 24: each block's friction (infinity too) and the slip and lift flag go to the helper;
// the samples' slip and lift come back, and only when the history carries them.
TEST(ProtocolTest, FrictionAndSlipAndLiftTravel) {
  BulletInput in = SomeInput();
  in.blocks[0].friction = 0.2;
  in.slip_and_lift = true;
  const BulletInput b = ParseInput(SerializeInput(in));
  EXPECT_EQ(b.blocks[0].friction, 0.2);
  EXPECT_TRUE(std::isinf(b.blocks[1].friction));
  EXPECT_TRUE(b.slip_and_lift);
  EXPECT_FALSE(ParseInput(SerializeInput(SomeInput())).slip_and_lift);

  for (const bool tracked : {false, true}) {
    EngineResult a;
    a.history.blocks = 2;
    a.history.slip_and_lift = tracked;
    Sample smp(2, tracked);
    smp.t_s = 0.25;
    if (tracked) {
      smp.u_m = {-0.5, 1.0 / 3.0};
      smp.z_m = {0.0, 2e-3};
    }
    a.history.samples.push_back(smp);
    a.summary = nlohmann::json::object();
    const EngineResult r = ParseOutput(SerializeOutput(a));
    EXPECT_EQ(SerializeOutput(r), SerializeOutput(a));
    EXPECT_EQ(r.history.slip_and_lift, tracked);
    ASSERT_EQ(r.history.samples.size(), 1u);
    EXPECT_EQ(r.history.samples[0].u_m, smp.u_m);
    EXPECT_EQ(r.history.samples[0].z_m, smp.z_m);
  }
}

TEST(ProtocolTest, RefusesTruncatedForeignAndStaleData) {
  const std::string bytes = SerializeInput(SomeInput());
  for (size_t cut : {size_t{0}, size_t{5}, size_t{12}, bytes.size() / 2, bytes.size() - 1}) {
    EXPECT_THROW(ParseInput(bytes.substr(0, cut)), std::runtime_error) << cut;
  }
  EXPECT_THROW(ParseInput(bytes + "x"), std::runtime_error);
  // An output file is not an input file.
  EngineResult o;
  o.summary = nlohmann::json::object();
  EXPECT_THROW(ParseInput(SerializeOutput(o)), std::runtime_error);
  // Another version: the message says to rebuild both programs.
  std::string stale = bytes;
  stale[8] = static_cast<char>(stale[8] + 1);
  try {
    ParseInput(stale);
    ADD_FAILURE() << "accepted another protocol version";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("rebuild"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rockbench::bullet
