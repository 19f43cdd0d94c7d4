// Geometry of the drawing: block corners from a state (the scene's pivot chain, thesis sign
// convention), states between samples, the base displacement (the kinematic drive's ground path),
// the camera, and frame times.
#include "renders/drawn_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "motion/ground_displacement.h"
#include "scene/engine_settings.h"
#include "scene/stack_pose.h"
#include "tests/common/initial_state.h"
#include "tests/common/sample.h"
#include "tests/common/stack_scene.h"

namespace rockbench::renders {
namespace {

using testing_util::MakeSample;

// Corner positions are sums of a few products of metre-sized numbers: exact to ~1e-15 m; 1e-12 m
// leaves room for the order of operations.
constexpr double kTolM = 1e-12;

Scene TwoBlocks(double b1_w = 1.0, double h1 = 1.5, double b2_w = 0.6, double h2 = 1.2) {
  return testing_util::TwoBlockScene(b1_w, h1, 100.0, b2_w, h2, 30.0);
}

double Dist(Vec2 a, Vec2 b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// Clockwise tilt of a quad (thesis sign): the angle of its bottom edge below +x.
double TiltOf(const BlockCorners& q) {
  return -std::atan2(q[1].y - q[0].y, q[1].x - q[0].x);
}

void ExpectNear(Vec2 a, Vec2 b) {
  EXPECT_NEAR(a.x, b.x, kTolM);
  EXPECT_NEAR(a.y, b.y, kTolM);
}

TEST(PoseFor, AtRestBlock2IsCentredOnBlock1) {
  const DrawnStack p = PoseFor(TwoBlocks(), 0.0, 0.0);
  ExpectNear(p[0][0], {-0.5, 0.0});
  ExpectNear(p[0][2], {0.5, 1.5});
  ExpectNear(p[1][0], {-0.3, 1.5});
  ExpectNear(p[1][2], {0.3, 2.7});
}

TEST(PoseFor, PositiveTheta1PivotsAboutTheRightCornerClockwise) {
  const double th = 0.3;
  const DrawnStack p = PoseFor(TwoBlocks(), th, th);
  // The right base corner stays put; the left one lifts; the top moves right.
  ExpectNear(p[0][1], {0.5, 0.0});
  EXPECT_GT(p[0][0].y, 0.0);
  EXPECT_NEAR(p[0][0].y, std::sin(th), kTolM);
  EXPECT_GT(p[0][3].x, -0.5);
  EXPECT_NEAR(TiltOf(p[0]), th, kTolM);
  // Rigid: the sides keep their lengths.
  EXPECT_NEAR(Dist(p[0][0], p[0][1]), 1.0, kTolM);
  EXPECT_NEAR(Dist(p[0][1], p[0][2]), 1.5, kTolM);
}

TEST(PoseFor, NegativeTheta1PivotsAboutTheLeftCorner) {
  const double th = -0.25;
  const DrawnStack p = PoseFor(TwoBlocks(), th, th);
  ExpectNear(p[0][0], {-0.5, 0.0});
  EXPECT_NEAR(p[0][1].y, std::sin(-th), kTolM);
  EXPECT_LT(p[0][2].x, 0.5);
  EXPECT_NEAR(TiltOf(p[0]), th, kTolM);
}

TEST(PoseFor, LockedBlock2StaysCentredOnTheTiltedBlock1) {
  const double th = 0.2;
  const DrawnStack p = PoseFor(TwoBlocks(), th, th);
  // Block 2's base corners are block 1's top-face points at -+0.3 m from its centre.
  const Vec2 top_mid{0.5 * (p[0][2].x + p[0][3].x), 0.5 * (p[0][2].y + p[0][3].y)};
  const Vec2 along{std::cos(th), -std::sin(th)};
  ExpectNear(p[1][0], {top_mid.x - 0.3 * along.x, top_mid.y - 0.3 * along.y});
  ExpectNear(p[1][1], {top_mid.x + 0.3 * along.x, top_mid.y + 0.3 * along.y});
  EXPECT_NEAR(TiltOf(p[1]), th, kTolM);
}

TEST(PoseFor, Block2AheadOfBlock1PivotsAboutItsRightCorner) {
  // theta2 > theta1: block 2's right base corner stays where it is on block 1's top face.
  const double th1 = 0.1, th2 = 0.35;
  const DrawnStack locked = PoseFor(TwoBlocks(), th1, th1);
  const DrawnStack p = PoseFor(TwoBlocks(), th1, th2);
  ExpectNear(p[1][1], locked[1][1]);
  EXPECT_NEAR(TiltOf(p[1]), th2, kTolM);
  EXPECT_NEAR(Dist(p[1][1], p[1][2]), 1.2, kTolM);
}

TEST(PoseFor, Block2BehindBlock1PivotsAboutItsLeftCorner) {
  const double th1 = 0.1, th2 = -0.2;
  const DrawnStack locked = PoseFor(TwoBlocks(), th1, th1);
  const DrawnStack p = PoseFor(TwoBlocks(), th1, th2);
  ExpectNear(p[1][0], locked[1][0]);
  EXPECT_NEAR(TiltOf(p[1]), th2, kTolM);
}

TEST(PoseFor, Block2OnBlock1AtRestTiltsAboutItsCornerOnTheTopFace) {
  // Mode 4a: block 1 still, block 2 rocks on it about (b2, H1).
  const DrawnStack p = PoseFor(TwoBlocks(), 0.0, 0.2);
  ExpectNear(p[0][2], {0.5, 1.5});
  ExpectNear(p[1][1], {0.3, 1.5});
  EXPECT_NEAR(p[1][0].y, 1.5 + 0.6 * std::sin(0.2), kTolM);
}

// A block 2 wider than block 1 is refused by the scene reader (block2.width), so the pivot
// chain has no case for it (earlier versions drew it pivoting on block 1's corner).

TEST(PoseFor, IsTheEnginesPivotChain) {
  // The corners are those of the poses the engines start from (scene/stack_pose.h PlaceStack),
  // bit for bit: one geometry.
  const Scene s = TwoBlocks();
  const InitialState state = testing_util::Initial(0.12, -0.07, 0.3, -0.4);
  const DrawnStack p = PoseFor(s, state);
  const StackPlacement place = PlaceStack(s, state);
  const BlockCorners c1 = Corners(place.blocks[0], 0.5, 0.75);
  const BlockCorners c2 = Corners(place.blocks[1], 0.3, 0.6);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(p[0][i].x, c1[i].x);
    EXPECT_EQ(p[0][i].y, c1[i].y);
    EXPECT_EQ(p[1][i].x, c2[i].x);
    EXPECT_EQ(p[1][i].y, c2[i].y);
  }
}

// A stack of `n` blocks narrowing upwards: block k (1-based) is 1.0 - 0.05 (k - 1) m wide and
// 0.8 + 0.1 (k % 3) m high.
Scene Column(int n) {
  Scene s;
  for (int k = 1; k <= n; ++k) {
    s.blocks.push_back(BlockDef{
        .width_m = 1.0 - 0.05 * (k - 1), .height_m = 0.8 + 0.1 * (k % 3), .mass_kg = 50.0});
  }
  return s;
}

InitialState StateOf(const std::vector<double>& theta, const std::vector<double>& omega = {}) {
  InitialState state;
  for (size_t k = 0; k < theta.size(); ++k) state.theta_rad[k] = theta[k];
  for (size_t k = 0; k < omega.size(); ++k) state.omega_radps[k] = omega[k];
  return state;
}

TEST(PoseFor, ALockedColumnTurnsRigidlyAboutBlock1sCorner) {
  // Every block at the same angle and rate: the column is one rigid body turning about block
  // 1's right base corner (theta > 0) or its left one (theta < 0). Its corners are those at
  // rest turned about that corner.
  const Scene s = Column(8);
  for (double th : {0.15, -0.1}) {
    const DrawnStack rest = PoseFor(s, StateOf(std::vector<double>(8, 0.0)));
    const DrawnStack p = PoseFor(s, StateOf(std::vector<double>(8, th)));
    ASSERT_EQ(p.size(), 8u);
    const Vec2 pivot{th > 0 ? 0.5 : -0.5, 0.0};
    for (size_t k = 0; k < 8; ++k) {
      for (int i = 0; i < 4; ++i) {
        const Vec2 d = rest[k][i] - pivot;
        ExpectNear(p[k][i], {pivot.x + std::cos(th) * d.x + std::sin(th) * d.y,
                             pivot.y - std::sin(th) * d.x + std::cos(th) * d.y});
      }
    }
  }
  // At rest each block is centred on the one below, its base on the other's top.
  const DrawnStack rest = PoseFor(s, InitialState{});
  double y = 0.0;
  for (int k = 0; k < 8; ++k) {
    const double b = 0.5 * s.blocks[k].width_m, h = s.blocks[k].height_m;
    ExpectNear(rest[k][0], {-b, y});
    ExpectNear(rest[k][2], {b, y + h});
    y += h;
  }
}

TEST(PoseFor, EachBlockPivotsOnTheTopFaceOfTheOneBelow) {
  // Three blocks, the third tilted further right than the second (it pivots about its right
  // base corner) and the second back to the left of the first (about its left one): each
  // pivot is a corner of the block above lying on the top face of the block below, and each
  // block is tilted by its own angle.
  const Scene s = Column(3);
  const double th1 = 0.05, th2 = -0.04, th3 = 0.12;
  const DrawnStack p = PoseFor(s, StateOf({th1, th2, th3}));
  ASSERT_EQ(p.size(), 3u);
  EXPECT_NEAR(TiltOf(p[0]), th1, kTolM);
  EXPECT_NEAR(TiltOf(p[1]), th2, kTolM);
  EXPECT_NEAR(TiltOf(p[2]), th3, kTolM);
  ExpectNear(p[0][1], {0.5, 0.0});  // block 1 about its right corner
  // Block 2's left base corner: on block 1's top face, 0.475 m left of its middle (where it is
  // when locked).
  const DrawnStack locked12 = PoseFor(s, StateOf({th1, th1, th1}));
  ExpectNear(p[1][0], locked12[1][0]);
  // Block 3's right base corner: where it is when locked on block 2 (block 2 as it is now).
  const DrawnStack locked23 = PoseFor(s, StateOf({th1, th2, th2}));
  ExpectNear(p[2][1], locked23[2][1]);
  // And that point is on block 2's top face, 0.45 m right of its middle.
  const Vec2 top_mid = 0.5 * (p[1][2] + p[1][3]);
  ExpectNear(p[2][1], top_mid + 0.45 * Vec2{std::cos(th2), -std::sin(th2)});
  // Rigid blocks.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(Dist(p[k][0], p[k][1]), s.blocks[k].width_m, kTolM);
    EXPECT_NEAR(Dist(p[k][1], p[k][2]), s.blocks[k].height_m, kTolM);
  }
}

TEST(PoseFor, ZeroAnglesWithRatesMoveNoCorner) {
  const Scene s = Column(5);
  const DrawnStack rest = PoseFor(s, InitialState{});
  const DrawnStack p = PoseFor(s, StateOf({0, 0, 0, 0, 0}, {1.0, -2.0, 0.5, 0.5, -3.0}));
  for (int k = 0; k < 5; ++k) {
    for (int i = 0; i < 4; ++i) ExpectNear(p[k][i], rest[k][i]);
  }
}

TEST(PoseFor, BaseDisplacementShiftsEveryBlock) {
  const Scene s = Column(4);
  const DrawnStack a = PoseFor(s, StateOf({0.1, 0.2, 0.0, -0.1}));
  const DrawnStack b = PoseFor(s, StateOf({0.1, 0.2, 0.0, -0.1}), {0.25, -0.05});
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 4; ++i) ExpectNear(b[k][i], {a[k][i].x + 0.25, a[k][i].y - 0.05});
  }
}

TEST(PoseFor, AZeroAngleWithARateMovesNoCorner) {
  // At theta = 0 the pivot takes the side of the rate (PivotSide's tie-break); a rotation by
  // zero about either corner leaves every corner at rest.
  const DrawnStack rest = PoseFor(TwoBlocks(), 0.0, 0.0);
  for (const InitialState& state :
       {testing_util::Initial(0.0, 0.0, 1.5, 1.5), testing_util::Initial(0.0, 0.0, -2.0, 1.0)}) {
    const DrawnStack p = PoseFor(TwoBlocks(), state);
    for (int i = 0; i < 4; ++i) {
      ExpectNear(p[0][i], rest[0][i]);
      ExpectNear(p[1][i], rest[1][i]);
    }
  }
}

TEST(StackState, BlocksAboveTheHistorysTopRideLockedOnIt) {
  const Sample two = MakeSample({.t_s = 1.0,
                                 .theta1_rad = 0.1,
                                 .theta2_rad = 0.5,
                                 .omega1_radps = -0.2,
                                 .omega2_radps = 3.0});
  const InitialState s2 = StackState(two);
  EXPECT_EQ(s2.theta_rad[0], 0.1);
  EXPECT_EQ(s2.omega_radps[0], -0.2);
  EXPECT_EQ(s2.theta_rad[1], 0.5);
  EXPECT_EQ(s2.omega_radps[1], 3.0);
  EXPECT_EQ(s2.theta_rad[7], 0.5);
  // A single-block history drawn on a two-block scene: block 2 locked on block 1.
  const Sample one = MakeSample({.t_s = 1.0, .theta1_rad = 0.1, .omega1_radps = -0.2, .blocks = 1});
  const InitialState s1 = StackState(one);
  EXPECT_EQ(s1.theta_rad[1], 0.1);
  EXPECT_EQ(s1.omega_radps[1], -0.2);
}

TEST(PoseFor, SingleBlockHasNoBlock2) {
  Scene s = TwoBlocks();
  s.blocks.resize(1);
  const DrawnStack p = PoseFor(s, 0.1, 0.0);
  EXPECT_EQ(p.size(), 1u);
  ExpectNear(p[0][1], {0.5, 0.0});
}

TEST(PoseFor, BaseDisplacementShiftsEverything) {
  const DrawnStack a = PoseFor(TwoBlocks(), 0.1, 0.3);
  const DrawnStack b = PoseFor(TwoBlocks(), 0.1, 0.3, {0.25, -0.05});
  for (int i = 0; i < 4; ++i) {
    ExpectNear(b[0][i], {a[0][i].x + 0.25, a[0][i].y - 0.05});
    ExpectNear(b[1][i], {a[1][i].x + 0.25, a[1][i].y - 0.05});
  }
}

History Ramp() {
  History h;
  h.blocks = 2;
  for (int i = 0; i <= 10; ++i) {
    Sample s(2);
    s.t_s = 0.1 * i;
    s.theta_rad[0] = 0.01 * i;
    s.theta_rad[1] = -0.02 * i;
    s.mode = ConfigurationOf(i < 5 ? Mode::k1a : Mode::k2a, 2);
    h.samples.push_back(s);
  }
  return h;
}

TEST(StateAt, InterpolatesLinearlyAndTakesTheModeOfTheSampleBefore) {
  const History h = Ramp();
  const Sample s = StateAt(h, 0.45);
  EXPECT_NEAR(s.theta_rad[0], 0.045, 1e-15);
  EXPECT_NEAR(s.theta_rad[1], -0.09, 1e-15);
  EXPECT_EQ(s.mode, ConfigurationOf(Mode::k1a, 2));
  EXPECT_EQ(StateAt(h, 0.55).mode, ConfigurationOf(Mode::k2a, 2));
}

TEST(StateAt, HoldsBeforeTheFirstAndAfterTheLastSample) {
  const History h = Ramp();
  EXPECT_EQ(StateAt(h, -1.0).theta_rad[0], 0.0);
  EXPECT_NEAR(StateAt(h, 5.0).theta_rad[0], 0.1, 1e-15);
}

TEST(StateAt, AtAnEventTimeGivesThePostEventSample) {
  History h;
  h.samples = {MakeSample({.t_s = 0.0, .theta1_rad = 0.0}),
               MakeSample({.t_s = 1.0, .theta1_rad = 0.2, .omega1_radps = 1.0, .mode = Mode::k3a}),
               MakeSample({.t_s = 1.0, .theta1_rad = 0.2, .omega1_radps = -0.5, .mode = Mode::k3b}),
               MakeSample({.t_s = 2.0, .theta1_rad = 0.0, .mode = Mode::k3b})};
  const Sample s = StateAt(h, 1.0);
  EXPECT_EQ(s.mode, ConfigurationOf(Mode::k3b, 2));
  EXPECT_EQ(s.omega_radps[0], -0.5);
}

TEST(StateAt, RejectsAnEmptyHistory) {
  EXPECT_THROW(StateAt(History{}, 0.0), std::invalid_argument);
}

TEST(BaseDisplacement, SamplesAreInterpolatedAndHeld) {
  const auto d = BaseDisplacement::FromSamples(1.0, 0.5, {0.0, 1.0, 3.0}, {0.0, -1.0, -2.0});
  EXPECT_NEAR(d.At(1.25).x, 0.5, 1e-15);
  EXPECT_NEAR(d.At(1.75).y, -1.5, 1e-15);
  EXPECT_EQ(d.At(0.0).x, 0.0);
  EXPECT_EQ(d.At(9.0).x, 3.0);
  EXPECT_TRUE(BaseDisplacement().empty());
  EXPECT_EQ(BaseDisplacement().At(3.0).x, 0.0);
}

TEST(BaseDisplacement, FunctionIsCalled) {
  const auto d = BaseDisplacement::FromFunction([](double t) { return Vec2{2 * t, -t}; });
  EXPECT_EQ(d.At(1.5).x, 3.0);
  EXPECT_EQ(d.At(1.5).y, -1.5);
}

GroundMotion Harmonic(double amp_m, double w_radps, double dt_s, int samples) {
  // x(t) = A sin(w t) has a(t) = -A w^2 sin(w t); a record of it, linear between samples.
  std::vector<double> a;
  for (int i = 0; i < samples; ++i)
    a.push_back(-amp_m * w_radps * w_radps * std::sin(w_radps * i * dt_s));
  GroundMotion motion;
  motion.set_horizontal(MotionComponent::FromSamples(a, dt_s, 0.0, "test"));
  return motion;
}

TEST(IntegrateBaseDisplacement, IsTheKinematicDrivesGroundPath) {
  // The animation's ground is the path a kinematic-drive engine moves its ground along: the
  // scene's IntegrateGroundPath of the acceleration sampled on the engine's step grid, bit for
  // bit at the grid's points.
  const GroundMotion motion = Harmonic(0.05, 2.0 * std::numbers::pi, 0.005, 801);
  for (const double fc : {0.0, 0.2}) {
    const BaseIntegrationConfig config{.dt_s = 1e-3, .highpass_hz = fc, .run_duration_s = 4.0};
    const BaseDisplacement d = IntegrateBaseDisplacement(motion, 4.0, config);
    std::vector<double> ax, ay;
    SampleGroundAcceleration(motion, 1e-3, 4000, &ax, &ay);
    const GroundPath path = IntegrateGroundPath(ax, 1e-3, fc);
    ASSERT_EQ(path.u_m.size(), 4001u);
    for (int n : {0, 1, 250, 1999, 3333, 4000}) {
      // At t = n dt the interpolation weight is 0 (or rounds to within 1e-16 of a sample).
      EXPECT_NEAR(d.At(n * 1e-3).x, path.u_m[n], 1e-15) << "fc " << fc << ", n " << n;
    }
  }
}

TEST(IntegrateBaseDisplacement, WithoutCorrectionTheHarmonicDrifts) {
  // The default is the kinematic drive's default: no baseline correction. From rest, a = -A w^2
  // sin(w t) gives v = A w (cos w t - 1) and x = A sin(w t) - A w t: the drift a drive engine
  // sees. The leapfrog rule at dt = 1e-4 s (the default grid) differs from the exact integral
  // by about (w dt)^2 / 12 = 3e-8 relative; the record's linear interpolation between its samples
  // at h = 5 ms lowers the acceleration by about (w h)^2 / 12 = 8e-5 of itself, an error of that
  // fraction of the whole path, drift included: 2e-4 A (1 + w t) bounds both.
  const double amp_m = 0.05, w = 2.0 * std::numbers::pi;
  const BaseDisplacement d = IntegrateBaseDisplacement(Harmonic(amp_m, w, 0.005, 801), 4.0);
  for (double t : {0.25, 0.75, 1.3, 2.25, 3.75}) {
    EXPECT_NEAR(d.At(t).x, amp_m * (std::sin(w * t) - w * t), 2e-4 * amp_m * (1.0 + w * t))
        << "t = " << t;
    EXPECT_EQ(d.At(t).y, 0.0);
  }
}

TEST(IntegrateBaseDisplacement, TheHighPassRemovesTheDrift) {
  // With the kinematic drive's high-pass (4th-order zero-phase Butterworth) at 0.1 Hz the ramp
  // -A w t goes (a zero-phase low-pass keeps a straight line) and the 1 Hz harmonic keeps
  // r^4 / (1 + r^4) = 0.9999 of its amplitude (r = 10). The start-up transient of the ramp's kink
  // at t = 0 decays as exp(-0.707 2 pi 0.1 t), below 2e-4 A after 25 s, and the end's
  // reflection alike before the end at 60 s: 1e-3 A holds between 25 and 35 s.
  const double amp_m = 0.05, w = 2.0 * std::numbers::pi;
  const GroundMotion motion = Harmonic(amp_m, w, 0.005, 12001);
  const BaseIntegrationConfig config{.dt_s = 1e-3, .highpass_hz = 0.1, .run_duration_s = 60.0};
  const BaseDisplacement d = IntegrateBaseDisplacement(motion, 60.0, config);
  for (double t : {25.0, 27.3, 30.1, 32.75, 35.0}) {
    EXPECT_NEAR(d.At(t).x, amp_m * std::sin(w * t), 1e-3 * amp_m) << "t = " << t;
  }
  // A shorter window shows the same path: the filter still runs over the whole run.
  const BaseDisplacement part = IntegrateBaseDisplacement(motion, 10.0, config);
  for (double t : {0.5, 5.0, 9.5}) EXPECT_EQ(part.At(t).x, d.At(t).x) << "t = " << t;
}

TEST(IntegrateBaseDisplacement, AVerticalComponentMovesTheGroundUpAndDown) {
  GroundMotion motion;
  motion.set_vertical(MotionComponent::FromSamples({1.0, 1.0, 1.0}, 1.0, 0.0, "up"));
  const BaseDisplacement d = IntegrateBaseDisplacement(motion, 2.0, {.dt_s = 0.5});
  // Leapfrog from rest with a = 1: u_n = n (n + 1) / 2 dt^2 (u_4 = 2.5 m at t = 2 s).
  EXPECT_EQ(d.At(2.0).y, 2.5);
  EXPECT_EQ(d.At(2.0).x, 0.0);
}

TEST(BaseIntegrationFor, TakesTheScenesKinematicDrive) {
  Scene s = TwoBlocks();
  s.run.duration_s = 12.0;
  BaseIntegrationConfig c = BaseIntegrationFor(s);
  EXPECT_EQ(c.dt_s, 1e-4);
  EXPECT_EQ(c.highpass_hz, 0.0);
  EXPECT_EQ(c.run_duration_s, 12.0);
  // An inertial engine's settings are not the ground's path.
  SetEngineSetting(s, "bullet", "time_step", 1e-3);
  EXPECT_EQ(BaseIntegrationFor(s).dt_s, 1e-4);
  SetEngineSetting(s, "ode", "drive", std::string("kinematic"));
  SetEngineSetting(s, "ode", "time_step", 5e-4);
  SetEngineSetting(s, "ode", "kinematic_highpass_hz", std::int64_t{1});
  c = BaseIntegrationFor(s);
  EXPECT_EQ(c.dt_s, 5e-4);
  EXPECT_EQ(c.highpass_hz, 1.0);
}

TEST(BaseDisplacementSamples, CountsTheGridAndTheFiltersPads) {
  const GroundMotion motion = Harmonic(0.05, 1.0, 0.01, 101);
  EXPECT_EQ(BaseDisplacementSamples(motion, 1.0), 10001.0);
  EXPECT_EQ(BaseDisplacementSamples(motion, 1.0, {.dt_s = 1e-3, .highpass_hz = 0.5}),
            1001.0 + 2.0 * 2400.0);
  EXPECT_EQ(BaseDisplacementSamples(GroundMotion{}, 1.0), 0.0);
}

TEST(IntegrateBaseDisplacement, NoMotionGivesNoDisplacement) {
  EXPECT_TRUE(IntegrateBaseDisplacement(GroundMotion{}, 10.0).empty());
}

TEST(Camera, FrameTheBoxWithTrueProportions) {
  const Box box{-1.0, 1.0, 0.0, 3.0};
  const Camera cam = FitCamera(box, 10.0, 20.0, 400.0, 300.0);
  // Isotropic: a metre is as many pixels across as up.
  const Vec2 o = cam.ToPixel({0.0, 0.0}), x1 = cam.ToPixel({1.0, 0.0}),
             y1 = cam.ToPixel({0.0, 1.0});
  EXPECT_NEAR(x1.x - o.x, o.y - y1.y, 1e-9);
  // The box's height fills the viewport (it is the tighter direction); bottom edge kept.
  EXPECT_NEAR(cam.ToPixel({0.0, 0.0}).y, 320.0, 1e-9);
  EXPECT_NEAR(cam.ToPixel({0.0, 3.0}).y, 20.0, 1e-9);
  // Centred horizontally.
  EXPECT_NEAR(o.x, 210.0, 1e-9);
}

TEST(Camera, MotionBoxHoldsAnOverturningBlock) {
  Scene s = TwoBlocks();
  History h;
  h.blocks = 2;
  for (int i = 0; i <= 100; ++i) {
    const double th = 0.5 * std::numbers::pi * i / 100.0;
    h.samples.push_back(MakeSample({.t_s = 0.01 * i, .theta1_rad = th, .theta2_rad = th}));
  }
  const Box box = MotionBox(s, {&h}, {}, 0.0, 1.0);
  const Camera cam = FitCamera(box, 0, 0, 640, 360);
  for (const Sample& smp : h.samples) {
    const DrawnStack p = PoseFor(s, smp.theta_rad[0], smp.theta_rad[1]);
    for (const BlockCorners* q : {&p[0], &p[1]}) {
      for (const Vec2& c : *q) {
        const Vec2 px = cam.ToPixel(c);
        EXPECT_GE(px.x, 0.0);
        EXPECT_LE(px.x, 640.0);
        EXPECT_GE(px.y, 0.0);
        EXPECT_LE(px.y, 360.0);
      }
    }
  }
  // Lying on its right side the stack reaches x = 0.5 + 2.7 m.
  EXPECT_GE(box.x_max_m, 3.2);
  // Some ground is in view below the surface.
  EXPECT_LT(box.y_min_m, 0.0);
}

TEST(Camera, MotionBoxHoldsEveryBlockOfATallStack) {
  // Eight blocks rocking apart: every corner of every block at every sample is in the box, and
  // the box is as tall as the column (its height grows with the number of blocks).
  const Scene s = Column(8);
  History h;
  h.blocks = 8;
  for (int i = 0; i <= 50; ++i) {
    Sample smp(8);
    smp.t_s = 0.02 * i;
    for (int k = 0; k < 8; ++k) smp.theta_rad[k] = 0.05 * (k + 1) * std::sin(3.0 * smp.t_s + k);
    h.samples.push_back(smp);
  }
  const Box box = MotionBox(s, {&h}, {}, 0.0, 1.0);
  for (const Sample& smp : h.samples) {
    for (const BlockCorners& q : PoseFor(s, StackState(smp))) {
      for (const Vec2& c : q) {
        EXPECT_GE(c.x, box.x_min_m);
        EXPECT_LE(c.x, box.x_max_m);
        EXPECT_GE(c.y, box.y_min_m);
        EXPECT_LE(c.y, box.y_max_m);
      }
    }
  }
  double column_h = 0.0;
  for (const BlockDef& b : s.blocks) column_h += b.height_m;
  EXPECT_GE(box.y_max_m, column_h);
  // The ground strip below is a fifth of the column's height.
  EXPECT_LE(box.y_min_m, -0.2 * column_h);
}

TEST(FrameTimes, CountAndSpacingFollowFpsAndSpeed) {
  // 2 s of motion at 30 fps in 2x slow motion (speed 0.5): a 4 s video of 120 frames.
  const auto t = FrameTimes(1.0, 3.0, 30.0, 0.5);
  ASSERT_EQ(t.size(), 120u);
  EXPECT_EQ(t.front(), 1.0);
  EXPECT_NEAR(t[1] - t[0], 0.5 / 30.0, 1e-15);
  EXPECT_LT(t.back(), 3.0);
  EXPECT_EQ(FrameTimes(0.0, 0.0, 30.0, 1.0).size(), 1u);
  EXPECT_THROW(FrameTimes(0.0, 1.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(FrameTimes(0.0, 1.0, 30.0, -1.0), std::invalid_argument);
  EXPECT_THROW(FrameTimes(2.0, 1.0, 30.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace rockbench::renders
