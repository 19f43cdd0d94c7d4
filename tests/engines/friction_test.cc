// Friction from the scene (issue 24) in every engine of the build: a block's `friction` is the
// engine's Coulomb coefficient for that block and its support, each interface its own, and
// without the key an engine keeps its own friction setting. The engine histories then carry the
// slip u and lift z the reference defines (engines/common/monitor.cc).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/engine_suite.h"
#include "common/housner_scene.h"
#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "reference/benchmarks/sliding_forms.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "scene/history.h"
#include "scene/scene.h"

namespace rockbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kStep_s = 1e-4;  // every engine's default step

// Newmark's sliding block: B = 2 m, H = 1 m, 1000 kg, mu = 0.2 on the ground, at rest under a
// horizontal rectangular pulse of 0.5 g for 0.4 s from 0.1 s; 2 s, g = 9.81 m/s^2. It never
// rocks (mu < B/H: both base corners stay compressed) and slides from 0.1 s until 1.1 s.
Scene NewmarkScene() {
  Scene s;
  s.blocks = {BlockDef{.width_m = 2.0, .height_m = 1.0, .mass_kg = 1000.0, .friction = 0.2}};
  MotionDef d;
  d.key = "base.horizontal";
  d.kind = MotionKind::kRectangularPulse;
  d.amplitude_g = 0.5;
  d.duration_s = 0.4;
  d.start_s = 0.1;
  s.horizontal = d;
  s.run.duration_s = 2.0;
  s.run.output_interval_s = 0.01;
  s.run.gravity_mps2 = 9.81;
  return s;
}

// A column of three drums at rest (1.0, 0.94, 0.88 m wide; 2.0, 1.9, 1.8 m tall; 2500 kg/m^3)
// with the given friction per block, 0.05 s.
Scene ThreeDrumsAtRest(double mu1, double mu2, double mu3) {
  Scene s;
  const double mu[] = {mu1, mu2, mu3};
  for (int k = 0; k < 3; ++k) {
    const double B = 1.0 - 0.06 * k, H = 2.0 - 0.1 * k;
    s.blocks.push_back(BlockDef{.width_m = B,
                                .height_m = H,
                                .depth_m = 1.0,
                                .mass_kg = 2500.0 * B * H,
                                .density_kgpm3 = 2500.0,
                                .friction = mu[k]});
  }
  s.run.duration_s = 0.05;
  s.run.output_interval_s = 0.01;
  return s;
}

// The engine's own coefficient for a contact of two of its bodies, as its settings report it
// (summary.json settings: the combined value where the engine combines two bodies' values);
// infinity where it reports none (ODE's unbounded rows).
double OwnFriction(const nlohmann::json& settings) {
  const nlohmann::json& f =
      settings.contains("friction_combined") ? settings["friction_combined"] : settings["friction"];
  return f.is_number() ? f.get<double>() : kInf;
}

class EngineFriction : public ::testing::TestWithParam<std::string> {};

// Newmark's rigid-plastic slip, u = -(a - mu g) a T^2 / (2 mu g) with a = 0.5 g0 (g0 =
// 9.80665 m/s^2) and g = 9.81 m/s^2: -0.58806 m, against the engine's final u1 at its defaults.
// The engines step the base motion sampled at the step starts t_n (EngineInput), and the pulse
// holds at both ends of [0.1, 0.5] s: it acts for T + dt, so an exact engine slips by the closed
// form at T + dt, (1 + dt / T)^2 - 1 = 5.0e-4 more than at T. Beyond that sampling, measured
// (2026-11-27, dt 1e-4 s, each engine at its defaults): Bullet, ODE and DART 1.3e-9 of the slip,
// Siconos 1.4e-8, MuJoCo 5.3e-8 (its soft contact). The bounds below are ten times those. As
// d ln u / d mu = -(g / (a - mu g) + 1 / mu) = -8.3 here, they hold the coefficient the engine
// applies to within 2e-9 (Bullet, ODE, DART), 2e-8 (Siconos) and 6e-8 (MuJoCo). z1, the lowest base
// corner's height: at most 1.4e-10 m (ODE, DART), 1.8e-7 m (Siconos), 0 (Bullet), under the
// monitor's uplift threshold 1e-5 m; MuJoCo's block hops while it slides (below).
TEST_P(EngineFriction, NewmarksBlockSlidesByTheClosedForm) {
  ASSERT_NE(FindEngine(GetParam()), nullptr) << GetParam() << " is not built";
  const Scene scene = NewmarkScene();
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const EngineRun run = RunEngine(GetParam(), scene, motion);
  ASSERT_EQ(run.outcome.status, RunStatus::kCompleted) << run.summary.value("status_detail", "");
  ASSERT_TRUE(run.history.slip_and_lift);
  ASSERT_FALSE(run.history.samples.empty());
  EXPECT_EQ(run.summary["settings"]["interface_friction"], nlohmann::json::array({0.2}));

  // The pulse as the engine steps it: the step starts at which it is not zero.
  int held = 0;
  for (int n = 0; n * kStep_s < scene.run.duration_s; ++n) {
    held += motion.xg_mps2(n * kStep_s) != 0.0;
  }
  const double a = 0.5 * 9.80665, g = scene.run.gravity_mps2, T = 0.4;
  const double newmark = benchmarks::SlidingBlockUnderPulse(a, T, 0.2, g).slip_m;
  const double stepped = benchmarks::SlidingBlockUnderPulse(a, held * kStep_s, 0.2, g).slip_m;
  ASSERT_NEAR(newmark, -0.58806, 5e-6);
  ASSERT_EQ(held, 4001);  // T / dt + 1: both ends of the pulse are step starts

  const std::string& e = GetParam();
  // Box2D steps in single precision: its velocity, rounded to float's 6e-8 at each of the
  // 10^4 steps of the slide, walks by about sqrt(10^4) 6e-8 = 6e-6 of the slip (measured
  // 6.4e-6 at length_scale 1000, 2026-11-26); ten times that, as for the others.
  // Rapier (f32 too, and a contact soft at 300 Hz) slips 1.3e-4 more than the stepped closed
  // form (measured 2026-11-27); ten times that.
  const double engine_rel = e == "mujoco"    ? 5e-7
                            : e == "siconos" ? 1.5e-7
                            : e == "box2d"   ? 6.5e-5
                            : e == "rapier"  ? 1.3e-3
                                             : 1.5e-8;
  const double u = run.history.samples.back().u_m[0];
  EXPECT_NEAR(u, stepped, engine_rel * std::abs(stepped))
      << "u1 at " << run.history.samples.back().t_s;
  const double sampling_rel = std::pow(1.0 + kStep_s / T, 2) - 1.0;
  EXPECT_NEAR(u, newmark, (sampling_rel + engine_rel) * std::abs(newmark));
  // It stops sliding at Newmark's stick time, a T / (mu g) = 1.0 s after the pulse starts: from
  // then on the slip holds.
  for (const Sample& s : run.history.samples) {
    if (s.t_s > 0.1 + a * (T + kStep_s) / (0.2 * g) + 0.01) {
      EXPECT_NEAR(s.u_m[0], u, 1e-6) << "at " << s.t_s;
    }
  }

  double z_max = 0.0, z_min = 0.0;
  for (const Sample& s : run.history.samples) {
    z_max = std::max(z_max, s.z_m[0]);
    z_min = std::min(z_min, s.z_m[0]);
  }
  // Penetration: MuJoCo 2.7e-6 m (its soft contact, landing from its hops), Siconos 1.8e-7 m,
  // the others 1.4e-10 m; all below the monitor's uplift threshold, 1e-5 m.
  EXPECT_GT(z_min, -1e-5);
  if (e == "mujoco") {
    // MuJoCo lifts the sliding block: z1 up to 2.3 mm at 0.55 s, back to 1e-9 m once it sticks
    // (1.1 s). Not a tolerance: this is what MuJoCo 2.2.2 does at its defaults and ours (its
    // convex, soft contact does not hold a sliding contact's gap at zero; our reading, measured,
    // not traced term by term). The bound pins it so that a change is seen.
    EXPECT_LT(z_max, 3e-3);
    EXPECT_LT(std::abs(run.history.samples.back().z_m[0]), 1e-6);
  } else {
    EXPECT_LT(z_max, 1e-6);
  }
}

// Without a friction key an engine keeps its own coefficient: no slip and lift in the history,
// no per-interface friction in the settings, and passing the engine's own coefficient through
// the scene gives the same motion bit for bit (the scene's path reaches the same contacts).
// Housner's block, 1.5 s (its first impact at 0.698 s).
TEST_P(EngineFriction, WithoutTheKeyTheEngineKeepsItsOwnFriction) {
  ASSERT_NE(FindEngine(GetParam()), nullptr) << GetParam() << " is not built";
  const Scene scene = testing_util::HousnerHalfAngleRelease(1.5);
  const EngineRun own = RunEngine(GetParam(), scene, GroundMotion());
  ASSERT_EQ(own.outcome.status, RunStatus::kCompleted);
  EXPECT_FALSE(own.history.slip_and_lift);
  for (const Sample& s : own.history.samples) EXPECT_TRUE(s.u_m.empty() && s.z_m.empty());
  EXPECT_EQ(HistoryToCsv(own.history).rfind("t,theta1,omega1,mode\n", 0), 0u);
  const nlohmann::json& settings = own.summary["settings"];
  EXPECT_FALSE(settings.contains("interface_friction")) << settings.dump();

  const double mu = OwnFriction(settings);
  if (!std::isfinite(mu)) {
    // ODE's own rows are unbounded: no finite coefficient to pass.
    EXPECT_EQ(GetParam(), "ode");
    return;
  }
  Scene given = scene;
  given.blocks[0].friction = mu;
  const EngineRun same = RunEngine(GetParam(), given, GroundMotion());
  EXPECT_EQ(same.summary["settings"]["interface_friction"], nlohmann::json::array({mu}));
  ASSERT_EQ(same.history.samples.size(), own.history.samples.size());
  for (size_t i = 0; i < own.history.samples.size(); ++i) {
    const Sample& a = own.history.samples[i];
    const Sample& b = same.history.samples[i];
    ASSERT_EQ(a.theta_rad, b.theta_rad) << "at " << a.t_s;
    ASSERT_EQ(a.omega_radps, b.omega_radps) << "at " << a.t_s;
    ASSERT_EQ(a.mode, b.mode) << "at " << a.t_s;
  }
  EXPECT_EQ(same.history.events.size(), own.history.events.size());
}

// Each interface its own coefficient, where the engine combines two bodies' values in its own
// way (Bullet the product, DART the smaller, MuJoCo the larger): three drums with mu = 0.5, 0.2,
// 0.7 (the middle one below both its neighbours: no single value per DART shape gives it), and
// with the middle key absent (the engine's own there). The stack stays at rest, with as many
// contacts as without friction keys (no contact pair doubled): within 1e-5 rad (the monitor's
// tilt threshold), 1e-6 m of slip and 1e-5 m of lift (measured: at most 3.5e-9 rad, 1.2e-8 m
// and 1.1e-7 m) but for Siconos. Siconos at its defaults moves the drums in the first 0.04 s,
// then holds them: 1.2e-5 rad, 1.9e-4 m of slip (u2) and 9.6e-6 m of penetration (measured,
// mixed case; 4.4e-6 m of slip in the first). Its NSGS needs up to 1,126 iterations a step on
// this stack with unequal coefficients; past its cap of 1,000 (21 and 13 of the 500 steps here)
// the step is solved again by Lemke, which moves them. With siconos.solver_max_iterations =
// 100000 no step fails and they stay within 1.2e-8 rad and 4e-8 m; with every coefficient 10
// (no key) 2 of the 500 steps fail and they stay within 2.4e-8 rad. Its bounds are those
// measurements with a margin, stated here; they are not a tolerance of the per-pair coefficient,
// which the settings check exactly.
TEST_P(EngineFriction, EachInterfaceHasItsOwnCoefficient) {
  ASSERT_NE(FindEngine(GetParam()), nullptr) << GetParam() << " is not built";
  const EngineRun plain = RunEngine(GetParam(), ThreeDrumsAtRest(kInf, kInf, kInf), GroundMotion());
  const double own = OwnFriction(plain.summary["settings"]);
  const nlohmann::json own_json = std::isfinite(own) ? nlohmann::json(own) : nlohmann::json();

  struct Case {
    double mu[3];
    nlohmann::json expected;
  };
  const Case cases[] = {{{0.5, 0.2, 0.7}, {0.5, 0.2, 0.7}},
                        {{0.5, kInf, 0.3}, {0.5, own_json, 0.3}}};
  for (const Case& c : cases) {
    const EngineRun run =
        RunEngine(GetParam(), ThreeDrumsAtRest(c.mu[0], c.mu[1], c.mu[2]), GroundMotion());
    const nlohmann::json& settings = run.summary["settings"];
    EXPECT_EQ(settings["interface_friction"], c.expected) << settings.dump();
    EXPECT_EQ(run.outcome.status, RunStatus::kCompleted);
    const bool siconos = GetParam() == "siconos";
    const double tilt = siconos ? 2e-5 : 1e-5, slip = siconos ? 3e-4 : 1e-6;
    const double lift = siconos ? 2e-5 : 1e-5;
    for (int k = 0; k < 3; ++k) EXPECT_LT(run.outcome.peak_theta_rad[k], tilt) << k;
    ASSERT_TRUE(run.history.slip_and_lift);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(std::abs(run.history.samples.back().u_m[k]), slip) << "u" << k + 1;
      EXPECT_LT(std::abs(run.history.samples.back().z_m[k]), lift) << "z" << k + 1;
    }
    if (run.summary.contains("diagnostics") &&
        run.summary["diagnostics"].contains("max_contacts")) {
      EXPECT_EQ(run.summary["diagnostics"]["max_contacts"],
                plain.summary["diagnostics"]["max_contacts"]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltEngines, EngineFriction,
                         ::testing::ValuesIn(testing_util::SuiteEngines()),
                         testing_util::EngineTestName);

}  // namespace
}  // namespace rockbench
