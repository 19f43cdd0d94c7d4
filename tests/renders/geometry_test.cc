// Geometry of the drawing: block corners from a state (thesis sign convention), states between
// samples, base displacement and its double integration, the camera, and frame times.
#include "renders/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rockbench::renders {
namespace {

// Corner positions are sums of a few products of metre-sized numbers: exact to ~1e-15 m; 1e-12 m
// leaves room for the order of operations.
constexpr double kTolM = 1e-12;

Scene TwoBlocks(double b1_w = 1.0, double h1 = 1.5, double b2_w = 0.6, double h2 = 1.2) {
  Scene s;
  s.block1 = {.width_m = b1_w, .height_m = h1, .mass_kg = 100.0};
  s.block2 = BlockDef{.width_m = b2_w, .height_m = h2, .mass_kg = 30.0};
  return s;
}

double Dist(Vec2 a, Vec2 b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
}

// Clockwise tilt of a quad (thesis sign): the angle of its bottom edge below +x.
double TiltOf(const Quad& q) {
  return -std::atan2(q[1].y_m - q[0].y_m, q[1].x_m - q[0].x_m);
}

void ExpectNear(Vec2 a, Vec2 b) {
  EXPECT_NEAR(a.x_m, b.x_m, kTolM);
  EXPECT_NEAR(a.y_m, b.y_m, kTolM);
}

TEST(PoseFor, AtRestBlock2IsCentredOnBlock1) {
  const StackPose p = PoseFor(TwoBlocks(), 0.0, 0.0);
  ExpectNear(p.block1[0], {-0.5, 0.0});
  ExpectNear(p.block1[2], {0.5, 1.5});
  ExpectNear(p.block2[0], {-0.3, 1.5});
  ExpectNear(p.block2[2], {0.3, 2.7});
}

TEST(PoseFor, PositiveTheta1PivotsAboutTheRightCornerClockwise) {
  const double th = 0.3;
  const StackPose p = PoseFor(TwoBlocks(), th, th);
  // The right base corner stays put; the left one lifts; the top moves right.
  ExpectNear(p.block1[1], {0.5, 0.0});
  EXPECT_GT(p.block1[0].y_m, 0.0);
  EXPECT_NEAR(p.block1[0].y_m, std::sin(th), kTolM);
  EXPECT_GT(p.block1[3].x_m, -0.5);
  EXPECT_NEAR(TiltOf(p.block1), th, kTolM);
  // Rigid: the sides keep their lengths.
  EXPECT_NEAR(Dist(p.block1[0], p.block1[1]), 1.0, kTolM);
  EXPECT_NEAR(Dist(p.block1[1], p.block1[2]), 1.5, kTolM);
}

TEST(PoseFor, NegativeTheta1PivotsAboutTheLeftCorner) {
  const double th = -0.25;
  const StackPose p = PoseFor(TwoBlocks(), th, th);
  ExpectNear(p.block1[0], {-0.5, 0.0});
  EXPECT_NEAR(p.block1[1].y_m, std::sin(-th), kTolM);
  EXPECT_LT(p.block1[2].x_m, 0.5);
  EXPECT_NEAR(TiltOf(p.block1), th, kTolM);
}

TEST(PoseFor, LockedBlock2StaysCentredOnTheTiltedBlock1) {
  const double th = 0.2;
  const StackPose p = PoseFor(TwoBlocks(), th, th);
  // Block 2's base corners are block 1's top-face points at -+0.3 m from its centre.
  const Vec2 top_mid{0.5 * (p.block1[2].x_m + p.block1[3].x_m),
                     0.5 * (p.block1[2].y_m + p.block1[3].y_m)};
  const Vec2 along{std::cos(th), -std::sin(th)};
  ExpectNear(p.block2[0], {top_mid.x_m - 0.3 * along.x_m, top_mid.y_m - 0.3 * along.y_m});
  ExpectNear(p.block2[1], {top_mid.x_m + 0.3 * along.x_m, top_mid.y_m + 0.3 * along.y_m});
  EXPECT_NEAR(TiltOf(p.block2), th, kTolM);
}

TEST(PoseFor, Block2AheadOfBlock1PivotsAboutItsRightCorner) {
  // theta2 > theta1: block 2's right base corner stays where it is on block 1's top face.
  const double th1 = 0.1, th2 = 0.35;
  const StackPose locked = PoseFor(TwoBlocks(), th1, th1);
  const StackPose p = PoseFor(TwoBlocks(), th1, th2);
  ExpectNear(p.block2[1], locked.block2[1]);
  EXPECT_NEAR(TiltOf(p.block2), th2, kTolM);
  EXPECT_NEAR(Dist(p.block2[1], p.block2[2]), 1.2, kTolM);
}

TEST(PoseFor, Block2BehindBlock1PivotsAboutItsLeftCorner) {
  const double th1 = 0.1, th2 = -0.2;
  const StackPose locked = PoseFor(TwoBlocks(), th1, th1);
  const StackPose p = PoseFor(TwoBlocks(), th1, th2);
  ExpectNear(p.block2[0], locked.block2[0]);
  EXPECT_NEAR(TiltOf(p.block2), th2, kTolM);
}

TEST(PoseFor, Block2OnBlock1AtRestTiltsAboutItsCornerOnTheTopFace) {
  // Mode 4a: block 1 still, block 2 rocks on it about (b2, H1).
  const StackPose p = PoseFor(TwoBlocks(), 0.0, 0.2);
  ExpectNear(p.block1[2], {0.5, 1.5});
  ExpectNear(p.block2[1], {0.3, 1.5});
  EXPECT_NEAR(p.block2[0].y_m, 1.5 + 0.6 * std::sin(0.2), kTolM);
}

TEST(PoseFor, WiderBlock2PivotsOnBlock1sCorner) {
  const StackPose p = PoseFor(TwoBlocks(1.0, 1.5, 1.4, 1.0), 0.0, 0.1);
  // The contact point is block 1's top-right corner (0.5, 1.5): a point of block 2's base.
  const Vec2 a = p.block2[0], b = p.block2[1];
  const double cross = (b.x_m - a.x_m) * (1.5 - a.y_m) - (b.y_m - a.y_m) * (0.5 - a.x_m);
  EXPECT_NEAR(cross, 0.0, kTolM);
  EXPECT_NEAR(TiltOf(p.block2), 0.1, kTolM);
}

TEST(PoseFor, SingleBlockHasNoBlock2) {
  Scene s = TwoBlocks();
  s.block2.reset();
  const StackPose p = PoseFor(s, 0.1, 0.0);
  EXPECT_FALSE(p.has_block2);
  ExpectNear(p.block1[1], {0.5, 0.0});
}

TEST(PoseFor, BaseDisplacementShiftsEverything) {
  const StackPose a = PoseFor(TwoBlocks(), 0.1, 0.3);
  const StackPose b = PoseFor(TwoBlocks(), 0.1, 0.3, {0.25, -0.05});
  for (int i = 0; i < 4; ++i) {
    ExpectNear(b.block1[i], {a.block1[i].x_m + 0.25, a.block1[i].y_m - 0.05});
    ExpectNear(b.block2[i], {a.block2[i].x_m + 0.25, a.block2[i].y_m - 0.05});
  }
}

History Ramp() {
  History h;
  h.two_blocks = true;
  for (int i = 0; i <= 10; ++i) {
    Sample s;
    s.t_s = 0.1 * i;
    s.theta1_rad = 0.01 * i;
    s.theta2_rad = -0.02 * i;
    s.mode = i < 5 ? Mode::k1a : Mode::k2a;
    h.samples.push_back(s);
  }
  return h;
}

TEST(StateAt, InterpolatesLinearlyAndTakesTheModeOfTheSampleBefore) {
  const History h = Ramp();
  const Sample s = StateAt(h, 0.45);
  EXPECT_NEAR(s.theta1_rad, 0.045, 1e-15);
  EXPECT_NEAR(s.theta2_rad, -0.09, 1e-15);
  EXPECT_EQ(s.mode, Mode::k1a);
  EXPECT_EQ(StateAt(h, 0.55).mode, Mode::k2a);
}

TEST(StateAt, HoldsBeforeTheFirstAndAfterTheLastSample) {
  const History h = Ramp();
  EXPECT_EQ(StateAt(h, -1.0).theta1_rad, 0.0);
  EXPECT_NEAR(StateAt(h, 5.0).theta1_rad, 0.1, 1e-15);
}

TEST(StateAt, AtAnEventTimeGivesThePostEventSample) {
  History h;
  h.samples = {{.t_s = 0.0, .theta1_rad = 0.0},
               {.t_s = 1.0, .theta1_rad = 0.2, .omega1_radps = 1.0, .mode = Mode::k3a},
               {.t_s = 1.0, .theta1_rad = 0.2, .omega1_radps = -0.5, .mode = Mode::k3b},
               {.t_s = 2.0, .theta1_rad = 0.0, .mode = Mode::k3b}};
  const Sample s = StateAt(h, 1.0);
  EXPECT_EQ(s.mode, Mode::k3b);
  EXPECT_EQ(s.omega1_radps, -0.5);
}

TEST(StateAt, RejectsAnEmptyHistory) {
  EXPECT_THROW(StateAt(History{}, 0.0), std::invalid_argument);
}

TEST(BaseDisplacement, SamplesAreInterpolatedAndHeld) {
  const auto d = BaseDisplacement::FromSamples(1.0, 0.5, {0.0, 1.0, 3.0}, {0.0, -1.0, -2.0});
  EXPECT_NEAR(d.At(1.25).x_m, 0.5, 1e-15);
  EXPECT_NEAR(d.At(1.75).y_m, -1.5, 1e-15);
  EXPECT_EQ(d.At(0.0).x_m, 0.0);
  EXPECT_EQ(d.At(9.0).x_m, 3.0);
  EXPECT_TRUE(BaseDisplacement().empty());
  EXPECT_EQ(BaseDisplacement().At(3.0).x_m, 0.0);
}

TEST(BaseDisplacement, FunctionIsCalled) {
  const auto d = BaseDisplacement::FromFunction([](double t) { return Vec2{2 * t, -t}; });
  EXPECT_EQ(d.At(1.5).x_m, 3.0);
  EXPECT_EQ(d.At(1.5).y_m, -1.5);
}

TEST(IntegrateBaseDisplacement, RecoversAHarmonicDisplacement) {
  // x(t) = A sin(w t) has a(t) = -A w^2 sin(w t). Integrated from rest, v = A w (cos w t - 1):
  // the baseline correction removes the constant -A w (over whole cycles the fitted slope is
  // 0), leaving x = A sin(w t). Trapezoidal errors at dt = 0.005 s, w = 2 pi are ~(w dt)^2/12 =
  // 8e-5 relative, in the velocity and in the fit; over 4 s they stay below 1e-3 A. 1e-2 A
  // is far above that and far below the error of an uncorrected drift (A w t, ~1.2 A at 4 s).
  const double amp_m = 0.05, w = 2.0 * std::numbers::pi, dt = 0.005;
  std::vector<double> a;
  for (int i = 0; i <= 800; ++i) a.push_back(-amp_m * w * w * std::sin(w * i * dt));
  GroundMotion motion;
  motion.set_horizontal(MotionComponent::FromSamples(a, dt, 0.0, "test"));
  const BaseDisplacement d = IntegrateBaseDisplacement(motion, 4.0);
  for (double t : {0.25, 0.75, 1.3, 2.25, 3.75}) {
    EXPECT_NEAR(d.At(t).x_m, amp_m * std::sin(w * t), 1e-2 * amp_m) << "t = " << t;
    EXPECT_EQ(d.At(t).y_m, 0.0);
  }
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
  EXPECT_NEAR(x1.x_m - o.x_m, o.y_m - y1.y_m, 1e-9);
  // The box's height fills the viewport (it is the tighter direction); bottom edge kept.
  EXPECT_NEAR(cam.ToPixel({0.0, 0.0}).y_m, 320.0, 1e-9);
  EXPECT_NEAR(cam.ToPixel({0.0, 3.0}).y_m, 20.0, 1e-9);
  // Centred horizontally.
  EXPECT_NEAR(o.x_m, 210.0, 1e-9);
}

TEST(Camera, MotionBoxHoldsAnOverturningBlock) {
  Scene s = TwoBlocks();
  History h;
  h.two_blocks = true;
  for (int i = 0; i <= 100; ++i) {
    const double th = 0.5 * std::numbers::pi * i / 100.0;
    h.samples.push_back({.t_s = 0.01 * i, .theta1_rad = th, .theta2_rad = th});
  }
  const Box box = MotionBox(s, {&h}, {}, 0.0, 1.0);
  const Camera cam = FitCamera(box, 0, 0, 640, 360);
  for (const Sample& smp : h.samples) {
    const StackPose p = PoseFor(s, smp.theta1_rad, smp.theta2_rad);
    for (const Quad* q : {&p.block1, &p.block2}) {
      for (const Vec2& c : *q) {
        const Vec2 px = cam.ToPixel(c);
        EXPECT_GE(px.x_m, 0.0);
        EXPECT_LE(px.x_m, 640.0);
        EXPECT_GE(px.y_m, 0.0);
        EXPECT_LE(px.y_m, 360.0);
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
