// The engine's input: [bullet] settings checks, base motion on the step grid, and the
// kinematic drive's displacement (leapfrog double integration and baseline correction).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engines/bullet/bullet_settings.h"

namespace rockbench::bullet {
namespace {

Scene OneBlock() {
  Scene s;
  s.block1 = {1.0, 4.0, 1.0, 10000.0, 0.0};
  s.run.duration_s = 1.0;
  return s;
}

// Second difference of u divided by dt^2 at step n (u_{-1} from the velocity before step 0).
double SecondDifference(const std::vector<double>& u, double v_before, double dt, size_t n) {
  const double prev = n == 0 ? u[0] - v_before * dt : u[n - 1];
  return (u[n + 1] - 2.0 * u[n] + prev) / (dt * dt);
}

TEST(EngineInputTest, SamplesTheBaseMotionAtTheStepStarts) {
  Scene s = OneBlock();
  SetEngineSetting(s, "bullet", "time_step", 1e-3);
  s.run.duration_s = 0.0105;  // not a multiple of dt: 11 steps
  GroundMotion m;
  m.set_horizontal(MotionComponent::FromSamples({0.0, 1.0}, 0.01, 0.0, "ramp"));
  const BulletInput in = MakeBulletInput(s, m);
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
  const BulletInput still = MakeBulletInput(OneBlock(), GroundMotion());
  EXPECT_TRUE(still.drive.ax_mps2.empty());
  EXPECT_EQ(still.steps, 10000);
}

TEST(EngineInputTest, RejectsImpossibleSettingsNamingTheKey) {
  // Each bad value is refused naming where it was set and the key (bullet.<key>), with what was
  // expected: the [bullet] table's schema for the settings, the step count for the time step.
  struct Case {
    const char* key;
    SettingValue value;
  };
  const Case cases[] = {
      {"time_step", 0.0},
      {"time_step", -1e-3},
      {"time_step", 1e-12},  // too many steps
      {"solver_iterations", std::int64_t{0}},
      {"solver_iterations", 2.5},
      {"erp", 1.5},
      {"erp2", -0.1},
      {"restitution", 2.0},
      {"friction", -1.0},
      {"rolling_friction", std::nan("")},
      {"restitution_velocity_threshold", -1.0},
      {"margin", -0.01},
      {"ground_depth", 0.0},
      {"kinematic_highpass_hz", -0.1},
      {"precision", std::string("half")},
      {"drive", std::string("pushed")},
      {"split_impulse", 1.0},
  };
  for (const Case& c : cases) {
    Scene s = OneBlock();
    s.path = "scenes/x.toml";
    SetEngineSetting(s, "bullet", c.key, c.value);
    try {
      MakeBulletInput(s, GroundMotion());
      ADD_FAILURE() << "accepted a bad " << c.key;
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string("bullet.") + c.key + ":"), std::string::npos) << what;
      EXPECT_NE(what.find("scenes/x.toml"), std::string::npos) << what;
      EXPECT_NE(what.find("expected"), std::string::npos) << what;
    }
  }
  // An unknown key names the known ones.
  Scene s = OneBlock();
  SetEngineSetting(s, "bullet", "time_stp", 1e-3);
  try {
    MakeBulletInput(s, GroundMotion());
    ADD_FAILURE() << "accepted bullet.time_stp";
  } catch (const SceneError& e) {
    EXPECT_NE(
        std::string(e.what()).find("bullet.time_stp: unknown key (expected one of: time_step"),
        std::string::npos)
        << e.what();
  }
}

TEST(EngineInputTest, KinematicDisplacementWithoutCorrectionIsTheExactDoubleIntegral) {
  const double dt = 1e-3;
  std::vector<double> a(500);
  for (size_t n = 0; n < a.size(); ++n) a[n] = 3.0 * std::sin(7.0 * n * dt) + 0.5;
  double v_before = 1.0, peak = 0.0;
  const std::vector<double> u = KinematicDisplacement(a, dt, 0.0, &v_before, &peak);
  ASSERT_EQ(u.size(), a.size() + 1);
  EXPECT_EQ(u[0], 0.0);
  EXPECT_EQ(v_before, 0.0);
  // The ground's velocity change per step is exactly what the inertial drive gives the blocks.
  for (size_t n = 0; n < a.size(); ++n) {
    EXPECT_NEAR(SecondDifference(u, v_before, dt, n), a[n], 1e-9 * 3.5) << n;
  }
  EXPECT_DOUBLE_EQ(peak, *std::max_element(u.begin(), u.end()));
  // Constant acceleration: u_n = a dt^2 n (n + 1) / 2 (leapfrog from rest).
  const std::vector<double> c =
      KinematicDisplacement(std::vector<double>(100, 2.0), dt, 0.0, nullptr, nullptr);
  for (size_t n = 0; n <= 100; ++n) {
    EXPECT_NEAR(c[n], 2.0 * dt * dt * n * (n + 1) / 2.0, 1e-15);
  }
}

TEST(EngineInputTest, BaselineCorrectionRemovesDriftAndKeepsTheShaking) {
  const double dt = 1e-3, fc = 0.1;
  const size_t n = 20000;  // 20 s
  // 0.2 s of 1 m/s^2 leaves the ground drifting at 0.2 m/s: 4 m after 20 s.
  std::vector<double> pulse(n, 0.0);
  for (size_t k = 0; k < 200; ++k) pulse[k] = 1.0;
  double v0 = 0.0, raw = 0.0;
  const std::vector<double> u = KinematicDisplacement(pulse, dt, fc, &v0, &raw);
  EXPECT_NEAR(raw, 0.02 + 0.2 * 19.8,
              2e-4);  // 1/2 a t^2 in the pulse, then 0.2 m/s (+ leapfrog 1e-4)
  double peak = 0.0;
  for (double x : u) peak = std::max(peak, std::abs(x));
  // Measured: the corrected ground starts 0.103 m left (the zero-phase baseline sees the drift
  // coming), is back near 0 after 2 s and ends 1.3 mm from 0; it never goes beyond 0.108 m.
  EXPECT_LT(peak, 0.12);
  EXPECT_LT(std::abs(u.back()), 0.005);
  EXPECT_GT(std::abs(u.front()), 0.05);
  // The velocity before step 0 continues the corrected path: the ground starts moving
  // smoothly (second difference at step 0 matches its neighbours').
  EXPECT_NEAR(SecondDifference(u, v0, dt, 0) - pulse[0], SecondDifference(u, v0, dt, 1) - pulse[1],
              1e-5);

  // A 5 Hz harmonic, 2 s, 0.3 g: |H_HP(5 Hz)|^2 = 1 - 1.6e-7 leaves the shaking itself alone;
  // what changes is the burst's mean velocity A / omega = 0.094 m/s, removed by a slow ground
  // acceleration of measured 0.011 m/s^2 = 0.38% of A. Bound 0.5%.
  std::vector<double> h(n, 0.0);
  const double A = 0.3 * kStandardGravity_mps2;
  for (size_t k = 0; k < 2000; ++k) h[k] = A * std::sin(2.0 * std::numbers::pi * 5.0 * k * dt);
  const std::vector<double> uh = KinematicDisplacement(h, dt, fc, &v0, nullptr);
  double worst = 0.0;
  for (size_t k = 0; k < n; ++k) {
    worst = std::max(worst, std::abs(SecondDifference(uh, v0, dt, k) - h[k]));
  }
  EXPECT_LT(worst, 5e-3 * A);
}

TEST(EngineInputTest, KinematicDriveFillsTheGroundPathAndItsReport) {
  Scene s = OneBlock();
  s.run.duration_s = 2.0;
  SetEngineSetting(s, "bullet", "time_step", 1e-3);
  SetEngineSetting(s, "bullet", "drive", std::string("kinematic"));
  MotionDef h;
  h.key = "base.horizontal";
  h.kind = MotionKind::kHarmonic;
  h.amplitude_g = 0.2;
  h.frequency_hz = 3.0;
  h.duration_s = 1.0;
  s.horizontal = h;
  const GroundMotion m = GroundMotion::FromScene(s);
  const BulletInput in = MakeBulletInput(s, m);
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

}  // namespace
}  // namespace rockbench::bullet
