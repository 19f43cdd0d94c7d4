// The stack's pivot chain (scene/stack_pose.h), against closed forms: a block turned clockwise by
// theta about its right (theta > 0) or left (theta < 0) base corner, block 2 on block 1's top
// face about its own corner, the rate's tie-break at theta = 0, velocities along the chain, and
// the corners.
#include "scene/stack_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "tests/common/initial_state.h"

namespace rockbench {
namespace {

// Every position is a few products of metre-sized numbers with sines and cosines: exact to a
// few 1e-16 m; 1e-14 leaves room for a different order of operations in the closed forms.
constexpr double kTol = 1e-14;

// p turned clockwise by theta (thesis sign) about the origin.
Vec2 Clockwise(double theta, Vec2 p) {
  return {p.x * std::cos(theta) + p.y * std::sin(theta),
          -p.x * std::sin(theta) + p.y * std::cos(theta)};
}

void ExpectNear(Vec2 a, Vec2 b, const char* what) {
  EXPECT_NEAR(a.x, b.x, kTol) << what;
  EXPECT_NEAR(a.y, b.y, kTol) << what;
}

Vec2 Centre(const PlanarPose& p) {
  return {p.x_m, p.y_m};
}
Vec2 Velocity(const PlanarPose& p) {
  return {p.vx_mps, p.vy_mps};
}

constexpr double b1 = 0.6, h1 = 0.9, b2 = 0.4, h2 = 1.3;  // half widths and heights, m

// One block (b1, h1), or two with block 2 (b2, h2) on it, placed at `state` (widths and heights
// twice the half values: exact in binary).
StackPlacement Place(bool two_blocks, const InitialState& state) {
  std::vector<BlockDef> blocks = {BlockDef{.width_m = 2.0 * b1, .height_m = 2.0 * h1}};
  if (two_blocks) blocks.push_back(BlockDef{.width_m = 2.0 * b2, .height_m = 2.0 * h2});
  return PlaceStack(blocks, state);
}

TEST(PivotSide, TheAngleFirstThenTheRate) {
  EXPECT_EQ(PivotSide(0.1, -5.0), 1);
  EXPECT_EQ(PivotSide(-0.1, 5.0), -1);
  EXPECT_EQ(PivotSide(0.0, 2.0), 1);
  EXPECT_EQ(PivotSide(0.0, -2.0), -1);
  EXPECT_EQ(PivotSide(0.0, 0.0), 0);
}

TEST(PlaceStack, PositiveTiltTurnsBlock1AboutItsRightCorner) {
  const double th = 0.3, om = 1.7;
  const StackPlacement p = Place(false, testing_util::Initial(th, 0.0, om, 0.0));
  EXPECT_EQ(p.sides[0], 1);
  // G1 = P1 + R_cw(theta) (G1 - P1 at rest), P1 = (b1, 0).
  const Vec2 r = Clockwise(th, {-b1, h1});
  ExpectNear(Centre(p.blocks[0]), {b1 + r.x, r.y}, "G1");
  EXPECT_EQ(p.blocks[0].phi_rad, -th);
  // v = w x r with the counter-clockwise rate w = -omega.
  ExpectNear(Velocity(p.blocks[0]), {om * r.y, -om * r.x}, "vG1");
  EXPECT_EQ(p.blocks[0].w_radps, -om);
  // The right base corner stays on the ground, the left one lifts by 2 b1 sin(theta).
  const BlockCorners c = Corners(p.blocks[0], b1, h1);
  ExpectNear(c[1], {b1, 0.0}, "right base corner");
  EXPECT_NEAR(c[0].y, 2.0 * b1 * std::sin(th), kTol);
}

TEST(PlaceStack, NegativeTiltTurnsBlock1AboutItsLeftCorner) {
  const double th = -0.2, om = 0.4;
  const StackPlacement p = Place(false, testing_util::Initial(th, 0.0, om, 0.0));
  EXPECT_EQ(p.sides[0], -1);
  const Vec2 r = Clockwise(th, {b1, h1});
  ExpectNear(Centre(p.blocks[0]), {-b1 + r.x, r.y}, "G1");
  ExpectNear(Velocity(p.blocks[0]), {om * r.y, -om * r.x}, "vG1");
  const BlockCorners c = Corners(p.blocks[0], b1, h1);
  ExpectNear(c[0], {-b1, 0.0}, "left base corner");
  EXPECT_NEAR(c[1].y, -2.0 * b1 * std::sin(th), kTol);
}

TEST(PlaceStack, AtZeroAngleTheRateChoosesThePivot) {
  // A block upright and starting to rock: its centre is at (0, h1) whichever the side, but the
  // velocity is that of a turn about the corner the rate leans to: (omega h1, +-omega b1).
  for (const double om : {2.0, -2.0}) {
    const StackPlacement p = Place(false, testing_util::Initial(0.0, 0.0, om, 0.0));
    EXPECT_EQ(p.sides[0], om > 0.0 ? 1 : -1);
    ExpectNear(Centre(p.blocks[0]), {0.0, h1}, "G1");
    ExpectNear(Velocity(p.blocks[0]), {om * h1, std::abs(om) * b1}, "vG1");
  }
  // At rest: flat on its face, no pivot.
  const StackPlacement rest = Place(false, InitialState());
  EXPECT_EQ(rest.sides[0], 0);
  ExpectNear(Centre(rest.blocks[0]), {0.0, h1}, "G1 at rest");
  ExpectNear(Velocity(rest.blocks[0]), {0.0, 0.0}, "vG1 at rest");
}

TEST(PlaceStack, Block2TurnsAboutItsOwnCornerOnBlock1sTopFace) {
  // theta2 > theta1: block 2 about its right base corner Q2 = (b2, 2 h1) of block 1's rest
  // frame, carried by block 1's turn; theta2 < theta1: about its left one.
  for (const auto& [th1, th2] :
       {std::pair{0.1, 0.35}, std::pair{0.1, -0.2}, std::pair{-0.15, -0.1}}) {
    const StackPlacement p = Place(true, testing_util::Initial(th1, th2, 0.0, 0.0));
    const int s1 = th1 > 0.0 ? 1 : -1, s2 = th2 > th1 ? 1 : -1;
    EXPECT_EQ(p.sides[0], s1);
    EXPECT_EQ(p.sides[1], s2);
    const Vec2 p1{s1 * b1, 0.0};
    const Vec2 q2 = p1 + Clockwise(th1, Vec2{s2 * b2, 2.0 * h1} - p1);
    const Vec2 g2 = q2 + Clockwise(th2, Vec2{-s2 * b2, h2});
    ExpectNear(Centre(p.blocks[1]), g2, "G2");
    EXPECT_EQ(p.blocks[1].phi_rad, -th2);
    // Q2 is block 2's pivot corner: bottom-right for s2 = +1, bottom-left for -1.
    const BlockCorners c2 = Corners(p.blocks[1], b2, h2);
    ExpectNear(c2[s2 > 0 ? 1 : 0], q2, "Q2");
  }
}

TEST(PlaceStack, LockedBlock2RidesBlock1AndItsRelativeRateChoosesItsPivot) {
  const double th = 0.12, om1 = 0.8;
  for (const double om2 : {1.5, 0.2}) {
    const StackPlacement p = Place(true, testing_util::Initial(th, th, om1, om2));
    const int s2 = om2 > om1 ? 1 : -1;
    EXPECT_EQ(p.sides[1], s2);
    // Centred on block 1's top face: G2 = P1 + R_cw(theta) ((0, 2 h1 + h2) - P1).
    const Vec2 p1{b1, 0.0};
    ExpectNear(Centre(p.blocks[1]), p1 + Clockwise(th, Vec2{0.0, 2.0 * h1 + h2} - p1), "G2");
    // v_G2 = w1 x (Q2 - P1) + w2 x (G2 - Q2), w = -omega.
    const Vec2 q2 = p1 + Clockwise(th, Vec2{s2 * b2, 2.0 * h1} - p1);
    const Vec2 r1 = q2 - p1, r2 = Clockwise(th, {-s2 * b2, h2});
    ExpectNear(Velocity(p.blocks[1]), {om1 * r1.y + om2 * r2.y, -om1 * r1.x - om2 * r2.x}, "vG2");
  }
}

TEST(PlaceStack, VelocitiesAreTheTimeDerivativesOfThePositions) {
  // Along theta_i(t) = theta_i + omega_i t the centres move with the velocities PlaceStack
  // gives (pivots fixed: no angle crosses zero). Central differences at dt = 1e-5 s are exact to
  // (dt^2 / 6) |x'''| ~ 1e-10 m/s here (rates ~1 rad/s on metre arms); 1e-8 m/s bounds that and
  // the rounding (1e-16 m / 1e-5 s).
  const InitialState s = testing_util::Initial(0.2, 0.45, -0.7, 1.1);
  const double dt = 1e-5;
  auto at = [&](double t) {
    return Place(true, testing_util::Initial(s.theta_rad[0] + s.omega_radps[0] * t,
                                             s.theta_rad[1] + s.omega_radps[1] * t,
                                             s.omega_radps[0], s.omega_radps[1]));
  };
  const StackPlacement p = at(0.0), a = at(-dt), b = at(dt);
  for (const auto& [now, before, after] : {std::tuple{p.blocks[0], a.blocks[0], b.blocks[0]},
                                           std::tuple{p.blocks[1], a.blocks[1], b.blocks[1]}}) {
    EXPECT_NEAR(now.vx_mps, (after.x_m - before.x_m) / (2.0 * dt), 1e-8);
    EXPECT_NEAR(now.vy_mps, (after.y_m - before.y_m) / (2.0 * dt), 1e-8);
    EXPECT_NEAR(now.w_radps, (after.phi_rad - before.phi_rad) / (2.0 * dt), 1e-8);
  }
}

TEST(StackCornersAt, AtRestBlock2IsCentredOnBlock1) {
  Scene scene;
  scene.blocks = {BlockDef{.width_m = 2.0 * b1, .height_m = 2.0 * h1, .mass_kg = 100.0},
                  BlockDef{.width_m = 2.0 * b2, .height_m = 2.0 * h2, .mass_kg = 30.0}};
  const StackCorners c = StackCornersAt(scene, {});
  ASSERT_EQ(c.blocks.size(), 2u);
  ExpectNear(c.blocks[0][0], {-b1, 0.0}, "block 1 bottom-left");
  ExpectNear(c.blocks[0][2], {b1, 2.0 * h1}, "block 1 top-right");
  ExpectNear(c.blocks[1][0], {-b2, 2.0 * h1}, "block 2 bottom-left");
  ExpectNear(c.blocks[1][2], {b2, 2.0 * (h1 + h2)}, "block 2 top-right");
  scene.blocks.resize(1);
  EXPECT_EQ(StackCornersAt(scene, testing_util::Initial(0.1, 0.0, 0.0, 0.0)).blocks.size(), 1u);
}

// ---------------------------------------------------------------------------------------------
// N blocks (issue 23): the chain P_(k+1) = P_k + R(phi_k)((s_(k+1) b_(k+1), 2 h_k) - (s_k b_k, 0)).

// A stack of n blocks, each no wider than the one below (tapering drums and a slender top).
std::vector<BlockDef> Stack(int n) {
  std::vector<BlockDef> blocks;
  for (int k = 0; k < n; ++k) {
    const double width = 1.2 - 0.07 * k, height = 0.6 + 0.23 * ((k * 5) % 3);
    blocks.push_back(BlockDef{.width_m = width, .height_m = height, .mass_kg = 100.0 + k});
  }
  return blocks;
}

InitialState State(const std::vector<double>& theta, const std::vector<double>& omega) {
  InitialState s;
  for (size_t k = 0; k < theta.size(); ++k) {
    s.theta_rad[k] = theta[k];
    s.omega_radps[k] = omega[k];
  }
  return s;
}

// A point of the base frame in a block's own frame (its centre, its axes).
Vec2 InFrameOf(const PlanarPose& pose, Vec2 p) {
  return Rotate(-pose.phi_rad, p - Centre(pose));
}

TEST(PlaceStackN, ALockedColumnTurnsAsOneBodyAboutBlock1sCorner) {
  // Every block at the same angle and rate: the column is one rigid body turned clockwise by
  // theta about block 1's base corner P1 = (+-b1, 0); each block's corners are its rest corners
  // turned so, its centre moves with omega x (G - P1).
  for (int n = 3; n <= 6; ++n) {
    for (const double th : {0.13, -0.21}) {
      SCOPED_TRACE(testing::Message() << n << " blocks, theta " << th);
      const std::vector<BlockDef> blocks = Stack(n);
      const double om = -0.7;
      const StackPlacement p =
          PlaceStack(blocks, State(std::vector<double>(n, th), std::vector<double>(n, om)));
      ASSERT_EQ(p.blocks.size(), static_cast<size_t>(n));
      ASSERT_EQ(p.sides.size(), static_cast<size_t>(n));
      const int s1 = th > 0.0 ? 1 : -1;
      EXPECT_EQ(p.sides[0], s1);
      for (int k = 1; k < n; ++k) EXPECT_EQ(p.sides[k], 0) << "interface " << k + 1;
      const Vec2 p1{s1 * 0.5 * blocks[0].width_m, 0.0};
      double base = 0.0;  // block k's base height at rest
      for (int k = 0; k < n; ++k) {
        const double b = 0.5 * blocks[k].width_m, h = 0.5 * blocks[k].height_m;
        const BlockCorners c = Corners(p.blocks[k], b, h);
        const Vec2 rest[4] = {{-b, base}, {b, base}, {b, base + 2.0 * h}, {-b, base + 2.0 * h}};
        for (int i = 0; i < 4; ++i) ExpectNear(c[i], p1 + Clockwise(th, rest[i] - p1), "corner");
        const Vec2 r = Centre(p.blocks[k]) - p1;
        ExpectNear(Velocity(p.blocks[k]), {om * r.y, -om * r.x}, "vG");
        EXPECT_EQ(p.blocks[k].phi_rad, -th);
        EXPECT_EQ(p.blocks[k].w_radps, -om);
        base += 2.0 * h;
      }
    }
  }
}

TEST(PlaceStackN, EveryBlocksBaseCornersRestOnTheTopFaceOfTheBlockBelow) {
  // Relative angles of both signs: block k's pivot corner (on the side of theta_k -
  // theta_(k-1)) is on block k - 1's top face at (s_k b_k, h_(k-1)) in block k - 1's frame; its
  // other base corner is 2 b_k sin|theta_k - theta_(k-1)| above that face. Block 1 likewise on
  // the ground.
  const std::vector<double> theta = {0.08, 0.19, 0.11, -0.05, -0.02, 0.3};
  const std::vector<double> omega = {0.4, -1.0, 0.2, 0.0, 0.6, -0.3};
  for (int n = 3; n <= 6; ++n) {
    SCOPED_TRACE(testing::Message() << n << " blocks");
    const std::vector<BlockDef> blocks = Stack(n);
    const StackPlacement p = PlaceStack(blocks, State(theta, omega));
    {
      const double b = 0.5 * blocks[0].width_m, h = 0.5 * blocks[0].height_m;
      const BlockCorners c = Corners(p.blocks[0], b, h);
      EXPECT_EQ(p.sides[0], 1);
      ExpectNear(c[1], {b, 0.0}, "block 1's pivot corner");
      EXPECT_NEAR(c[0].y, 2.0 * b * std::sin(theta[0]), kTol);
    }
    for (int k = 1; k < n; ++k) {
      const double rel = theta[k] - theta[k - 1];
      const int side = rel > 0.0 ? 1 : -1;
      EXPECT_EQ(p.sides[k], side) << "interface " << k + 1;
      const double b = 0.5 * blocks[k].width_m, h = 0.5 * blocks[k].height_m;
      const double h_below = 0.5 * blocks[k - 1].height_m;
      const BlockCorners c = Corners(p.blocks[k], b, h);
      const Vec2 pivot = InFrameOf(p.blocks[k - 1], c[side > 0 ? 1 : 0]);
      const Vec2 other = InFrameOf(p.blocks[k - 1], c[side > 0 ? 0 : 1]);
      ExpectNear(pivot, {side * b, h_below}, "pivot corner on the face below");
      EXPECT_NEAR(other.y - h_below, 2.0 * b * std::sin(std::abs(rel)), kTol) << k + 1;
      EXPECT_NEAR(other.x, side * b * (1.0 - 2.0 * std::cos(rel)), kTol) << k + 1;
    }
  }
}

TEST(PlaceStackN, VelocitiesAreTheTimeDerivativesOfThePositions) {
  // Along theta_i(t) = theta_i + omega_i t, no relative angle crossing zero within +-dt: the
  // central differences of the centres and angles are the velocities (1e-8 m/s, as for two).
  const std::vector<double> theta = {0.08, 0.19, 0.11, -0.05, -0.02, 0.3};
  const std::vector<double> omega = {0.4, -1.0, 0.2, 0.0, 0.6, -0.3};
  const double dt = 1e-5;
  for (int n = 3; n <= 6; ++n) {
    SCOPED_TRACE(testing::Message() << n << " blocks");
    const std::vector<BlockDef> blocks = Stack(n);
    auto at = [&](double t) {
      std::vector<double> th(theta.begin(), theta.begin() + n);
      for (int k = 0; k < n; ++k) th[k] += omega[k] * t;
      return PlaceStack(blocks, State(th, omega));
    };
    const StackPlacement p = at(0.0), a = at(-dt), b = at(dt);
    EXPECT_EQ(a.sides, p.sides);
    EXPECT_EQ(b.sides, p.sides);
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(p.blocks[k].vx_mps, (b.blocks[k].x_m - a.blocks[k].x_m) / (2.0 * dt), 1e-8) << k;
      EXPECT_NEAR(p.blocks[k].vy_mps, (b.blocks[k].y_m - a.blocks[k].y_m) / (2.0 * dt), 1e-8) << k;
      EXPECT_NEAR(p.blocks[k].w_radps, (b.blocks[k].phi_rad - a.blocks[k].phi_rad) / (2.0 * dt),
                  1e-8)
          << k;
    }
  }
}

TEST(PlaceStackN, OneBlockHasOnePoseAndNoBlockIsAnError) {
  const StackPlacement one = Place(false, testing_util::Initial(0.1, 0, 0, 0));
  EXPECT_EQ(one.blocks.size(), 1u);
  EXPECT_EQ(one.sides, std::vector<int>{1});
  EXPECT_THROW(PlaceStack(std::vector<BlockDef>{}, InitialState()), std::invalid_argument);
}

TEST(StackCornersAt, AtRestEveryBlockIsCentredOnTheOneBelow) {
  Scene scene;
  scene.blocks = Stack(5);
  const StackCorners c = StackCornersAt(scene, {});
  ASSERT_EQ(c.blocks.size(), 5u);
  double base = 0.0;
  for (int k = 0; k < 5; ++k) {
    const double b = 0.5 * scene.blocks[k].width_m, h = 0.5 * scene.blocks[k].height_m;
    ExpectNear(c.blocks[k][0], {-b, base}, "bottom-left");
    ExpectNear(c.blocks[k][2], {b, base + 2.0 * h}, "top-right");
    base += 2.0 * h;
  }
}

}  // namespace
}  // namespace rockbench
