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

#include "scene/engine_settings.h"
#include "scene/ground_displacement.h"
#include "scene/stack_pose.h"
#include "tests/common/initial_state.h"
#include "tests/common/sample.h"

namespace rockbench::renders {
namespace {

using testing_util::MakeSample;

// Corner positions are sums of a few products of metre-sized numbers: exact to ~1e-15 m; 1e-12 m
// leaves room for the order of operations.
constexpr double kTolM = 1e-12;

Scene TwoBlocks(double b1_w = 1.0, double h1 = 1.5, double b2_w = 0.6, double h2 = 1.2) {
  Scene s;
  s.blocks = {{.width_m = b1_w, .height_m = h1, .mass_kg = 100.0}};
  s.blocks.resize(1);
  s.blocks.push_back(BlockDef{.width_m = b2_w, .height_m = h2, .mass_kg = 30.0});
  return s;
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
  const StackCorners p = PoseFor(TwoBlocks(), 0.0, 0.0);
  ExpectNear(p.block1[0], {-0.5, 0.0});
  ExpectNear(p.block1[2], {0.5, 1.5});
  ExpectNear(p.block2[0], {-0.3, 1.5});
  ExpectNear(p.block2[2], {0.3, 2.7});
}

TEST(PoseFor, PositiveTheta1PivotsAboutTheRightCornerClockwise) {
  const double th = 0.3;
  const StackCorners p = PoseFor(TwoBlocks(), th, th);
  // The right base corner stays put; the left one lifts; the top moves right.
  ExpectNear(p.block1[1], {0.5, 0.0});
  EXPECT_GT(p.block1[0].y, 0.0);
  EXPECT_NEAR(p.block1[0].y, std::sin(th), kTolM);
  EXPECT_GT(p.block1[3].x, -0.5);
  EXPECT_NEAR(TiltOf(p.block1), th, kTolM);
  // Rigid: the sides keep their lengths.
  EXPECT_NEAR(Dist(p.block1[0], p.block1[1]), 1.0, kTolM);
  EXPECT_NEAR(Dist(p.block1[1], p.block1[2]), 1.5, kTolM);
}

TEST(PoseFor, NegativeTheta1PivotsAboutTheLeftCorner) {
  const double th = -0.25;
  const StackCorners p = PoseFor(TwoBlocks(), th, th);
  ExpectNear(p.block1[0], {-0.5, 0.0});
  EXPECT_NEAR(p.block1[1].y, std::sin(-th), kTolM);
  EXPECT_LT(p.block1[2].x, 0.5);
  EXPECT_NEAR(TiltOf(p.block1), th, kTolM);
}

TEST(PoseFor, LockedBlock2StaysCentredOnTheTiltedBlock1) {
  const double th = 0.2;
  const StackCorners p = PoseFor(TwoBlocks(), th, th);
  // Block 2's base corners are block 1's top-face points at -+0.3 m from its centre.
  const Vec2 top_mid{0.5 * (p.block1[2].x + p.block1[3].x), 0.5 * (p.block1[2].y + p.block1[3].y)};
  const Vec2 along{std::cos(th), -std::sin(th)};
  ExpectNear(p.block2[0], {top_mid.x - 0.3 * along.x, top_mid.y - 0.3 * along.y});
  ExpectNear(p.block2[1], {top_mid.x + 0.3 * along.x, top_mid.y + 0.3 * along.y});
  EXPECT_NEAR(TiltOf(p.block2), th, kTolM);
}

TEST(PoseFor, Block2AheadOfBlock1PivotsAboutItsRightCorner) {
  // theta2 > theta1: block 2's right base corner stays where it is on block 1's top face.
  const double th1 = 0.1, th2 = 0.35;
  const StackCorners locked = PoseFor(TwoBlocks(), th1, th1);
  const StackCorners p = PoseFor(TwoBlocks(), th1, th2);
  ExpectNear(p.block2[1], locked.block2[1]);
  EXPECT_NEAR(TiltOf(p.block2), th2, kTolM);
  EXPECT_NEAR(Dist(p.block2[1], p.block2[2]), 1.2, kTolM);
}

TEST(PoseFor, Block2BehindBlock1PivotsAboutItsLeftCorner) {
  const double th1 = 0.1, th2 = -0.2;
  const StackCorners locked = PoseFor(TwoBlocks(), th1, th1);
  const StackCorners p = PoseFor(TwoBlocks(), th1, th2);
  ExpectNear(p.block2[0], locked.block2[0]);
  EXPECT_NEAR(TiltOf(p.block2), th2, kTolM);
}

TEST(PoseFor, Block2OnBlock1AtRestTiltsAboutItsCornerOnTheTopFace) {
  // Mode 4a: block 1 still, block 2 rocks on it about (b2, H1).
  const StackCorners p = PoseFor(TwoBlocks(), 0.0, 0.2);
  ExpectNear(p.block1[2], {0.5, 1.5});
  ExpectNear(p.block2[1], {0.3, 1.5});
  EXPECT_NEAR(p.block2[0].y, 1.5 + 0.6 * std::sin(0.2), kTolM);
}

// A block 2 wider than block 1 is refused by the scene reader (block2.width), so the pivot
// chain has no case for it (earlier versions drew it pivoting on block 1's corner).

TEST(PoseFor, IsTheEnginesPivotChain) {
  // The corners are those of the poses the engines start from (scene/stack_pose.h PlaceStack),
  // bit for bit: one geometry.
  const Scene s = TwoBlocks();
  const InitialState state = testing_util::Initial(0.12, -0.07, 0.3, -0.4);
  const StackCorners p = PoseFor(s, state);
  const StackPlacement place = PlaceStack(0.5, 0.75, 0.3, 0.6, true, state);
  const BlockCorners c1 = Corners(place.block1, 0.5, 0.75), c2 = Corners(place.block2, 0.3, 0.6);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(p.block1[i].x, c1[i].x);
    EXPECT_EQ(p.block1[i].y, c1[i].y);
    EXPECT_EQ(p.block2[i].x, c2[i].x);
    EXPECT_EQ(p.block2[i].y, c2[i].y);
  }
}

TEST(PoseFor, AZeroAngleWithARateMovesNoCorner) {
  // At theta = 0 the pivot takes the side of the rate (PivotSide's tie-break); a rotation by
  // zero about either corner leaves every corner at rest.
  const StackCorners rest = PoseFor(TwoBlocks(), 0.0, 0.0);
  for (const InitialState& state :
       {testing_util::Initial(0.0, 0.0, 1.5, 1.5), testing_util::Initial(0.0, 0.0, -2.0, 1.0)}) {
    const StackCorners p = PoseFor(TwoBlocks(), state);
    for (int i = 0; i < 4; ++i) {
      ExpectNear(p.block1[i], rest.block1[i]);
      ExpectNear(p.block2[i], rest.block2[i]);
    }
  }
}

TEST(StackState, ASingleBlockHistoryLocksBlock2) {
  const Sample s = MakeSample({.t_s = 1.0,
                               .theta1_rad = 0.1,
                               .theta2_rad = 0.5,
                               .omega1_radps = -0.2,
                               .omega2_radps = 3.0});
  const InitialState one = StackState(s, false), two = StackState(s, true);
  EXPECT_EQ(one.theta_rad[1], 0.1);
  EXPECT_EQ(one.omega_radps[1], -0.2);
  EXPECT_EQ(two.theta_rad[1], 0.5);
  EXPECT_EQ(two.omega_radps[1], 3.0);
}

TEST(PoseFor, SingleBlockHasNoBlock2) {
  Scene s = TwoBlocks();
  s.blocks.resize(1);
  const StackCorners p = PoseFor(s, 0.1, 0.0);
  EXPECT_FALSE(p.has_block2);
  ExpectNear(p.block1[1], {0.5, 0.0});
}

TEST(PoseFor, BaseDisplacementShiftsEverything) {
  const StackCorners a = PoseFor(TwoBlocks(), 0.1, 0.3);
  const StackCorners b = PoseFor(TwoBlocks(), 0.1, 0.3, {0.25, -0.05});
  for (int i = 0; i < 4; ++i) {
    ExpectNear(b.block1[i], {a.block1[i].x + 0.25, a.block1[i].y - 0.05});
    ExpectNear(b.block2[i], {a.block2[i].x + 0.25, a.block2[i].y - 0.05});
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
    const StackCorners p = PoseFor(s, smp.theta_rad[0], smp.theta_rad[1]);
    for (const BlockCorners* q : {&p.block1, &p.block2}) {
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
