// The Bullet world: initial placement of the blocks by the pivot chain (positions and
// velocities), the planar constraint, bodies' settings, and the two base drives.
#include "engines/bullet/rocking_world.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "engines/common/engine_input.h"
#include "motion/ground_motion.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "scene/scene.h"
#include "tests/common/initial_state.h"

namespace rockbench::bullet {
namespace {

struct V2 {
  double x, y;
};

// The thesis's geometry (section 6.3): B1 = H1 = 1.25 m, B2 = 1 m, H2 = 2.5 m.
Scene ThesisStack(double theta1, double theta2, double omega1, double omega2) {
  Scene s;
  s.blocks = {{1.25, 1.25, 1.0, 3906.25, 0.0}};
  s.blocks.resize(1);
  s.blocks.push_back(BlockDef{1.0, 2.5, 1.0, 6250.0, 0.0});
  s.initial = testing_util::Initial(theta1, theta2, omega1, omega2);
  s.run.duration_s = 0.01;
  SetEngineSetting(s, "bullet", "split_impulse_threshold", 0.0);
  return s;
}

// Rotation of v by the thesis angle theta (clockwise for theta > 0).
V2 RotCw(double theta, V2 v) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * v.x + s * v.y, -s * v.x + c * v.y};
}

// Independent pivot chain: every corner of both blocks, written out corner by corner. Block 1
// turns by theta1 about its base corner on the side of the tilt; block 2 stands on block 1's
// top face with its pivot corner (right if theta2 > theta1, left if theta2 < theta1) and turns
// by theta2 about it. Order: bottom-left, bottom-right, top-right, top-left.
std::array<std::array<V2, 4>, 2> ChainCorners(const Scene& s) {
  const double B1 = s.blocks[0].width_m, H1 = s.blocks[0].height_m;
  const bool two = s.block_count() == 2;
  const double B2 = two ? s.blocks[1].width_m : 0.0, H2 = two ? s.blocks[1].height_m : 0.0;
  const double t1 = s.initial.theta_rad[0], t2 = s.initial.theta_rad[1];
  // Block 1's pivot at x = +-B1/2; a flat block is not turned (pivot irrelevant).
  const double p1x = t1 > 0 ? B1 / 2 : (t1 < 0 ? -B1 / 2 : 0.0);
  auto on1 = [&](V2 local_from_base_centre) {  // a point of block 1 given at rest
    const V2 r = RotCw(t1, {local_from_base_centre.x - p1x, local_from_base_centre.y});
    return V2{p1x + r.x, r.y};
  };
  std::array<std::array<V2, 4>, 2> c{};
  c[0] = {on1({-B1 / 2, 0}), on1({B1 / 2, 0}), on1({B1 / 2, H1}), on1({-B1 / 2, H1})};
  if (!two) return c;
  const double rel = t2 - t1;
  const double q_local = rel > 0 ? B2 / 2 : (rel < 0 ? -B2 / 2 : 0.0);  // on block 1's top
  const V2 q = on1({q_local, H1});
  auto on2 = [&](V2 at_rest_from_q) {  // block 2 point, offsets from its pivot at rest
    const V2 r = RotCw(t2, at_rest_from_q);
    return V2{q.x + r.x, q.y + r.y};
  };
  c[1] = {on2({-B2 / 2 - q_local, 0}), on2({B2 / 2 - q_local, 0}), on2({B2 / 2 - q_local, H2}),
          on2({-B2 / 2 - q_local, H2})};
  return c;
}

// World corners of a Bullet body (its z = 0 section), same order.
std::array<V2, 4> BodyCorners(btRigidBody* body, double b, double h) {
  const btTransform& t = body->getCenterOfMassTransform();
  std::array<V2, 4> out{};
  const double lx[4] = {-b, b, b, -b}, ly[4] = {-h, -h, h, h};
  for (int k = 0; k < 4; ++k) {
    const btVector3 p = t * btVector3(lx[k], ly[k], 0);
    out[k] = {p.x(), p.y()};
  }
  return out;
}

V2 PointVelocity(btRigidBody* body, V2 p) {
  const btVector3 rel = btVector3(p.x, p.y, 0) - body->getCenterOfMassPosition();
  const btVector3 v = body->getVelocityInLocalPoint(rel);
  return {v.x(), v.y()};
}

struct Case {
  double t1, t2, w1, w2;
  const char* mode;
};

TEST(RockingWorldTest, PlacesBothBlocksByThePivotChainTo1e12) {
  // One state per mode, with rates; 1e-12 m is a few ulps of the O(1 m) coordinates.
  const std::vector<Case> cases = {{0.10, 0.15, -0.3, 0.4, "1a"},   {0.10, 0.05, 0.2, -0.5, "2a"},
                                   {-0.10, -0.15, 0.3, -0.4, "1b"}, {-0.10, -0.05, -0.2, 0.5, "2b"},
                                   {0.12, 0.12, -0.7, -0.7, "3a"},  {-0.12, -0.12, 0.7, 0.7, "3b"},
                                   {0.0, 0.08, 0.0, 0.3, "4a"},     {0.0, -0.08, 0.0, -0.3, "4b"},
                                   {0.0, 0.0, 0.0, 0.0, "rest"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.mode);
    const Scene scene = ThesisStack(c.t1, c.t2, c.w1, c.w2);
    const BulletInput input = MakeBulletInput(scene, GroundMotion());
    RockingWorld world(input);
    const auto want = ChainCorners(scene);
    const auto got1 = BodyCorners(world.block1(), 0.625, 0.625);
    const auto got2 = BodyCorners(world.block2(), 0.5, 1.25);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(got1[k].x, want[0][k].x, 1e-12) << "block 1 corner " << k;
      EXPECT_NEAR(got1[k].y, want[0][k].y, 1e-12) << "block 1 corner " << k;
      EXPECT_NEAR(got2[k].x, want[1][k].x, 1e-12) << "block 2 corner " << k;
      EXPECT_NEAR(got2[k].y, want[1][k].y, 1e-12) << "block 2 corner " << k;
    }
    // The reference's own chain (reference/kinematics.h) agrees as well.
    const reference::Geometry geo = reference::MakeGeometry(scene);
    const auto mode = ParseMode(c.mode);
    ASSERT_TRUE(mode.has_value());
    const auto ref = reference::BlockCorners(geo, *mode, {c.t1, c.t2, c.w1, c.w2});
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(got1[k].x, ref[0][k].x, 1e-12);
      EXPECT_NEAR(got1[k].y, ref[0][k].y, 1e-12);
      EXPECT_NEAR(got2[k].x, ref[1][k].x, 1e-12);
      EXPECT_NEAR(got2[k].y, ref[1][k].y, 1e-12);
    }
    // Velocities consistent with the chain: block 1's pivot corner is still, block 2's pivot
    // moves with block 1's material point under it, angular rates are -omega about +z.
    EXPECT_NEAR(world.block1()->getAngularVelocity().z(), -c.w1, 1e-15);
    EXPECT_NEAR(world.block2()->getAngularVelocity().z(), -c.w2, 1e-15);
    const int pivot1 = c.t1 > 0 ? 1 : (c.t1 < 0 ? 0 : -1);
    if (pivot1 >= 0) {
      const V2 v = PointVelocity(world.block1(), got1[pivot1]);
      EXPECT_NEAR(v.x, 0.0, 1e-14);
      EXPECT_NEAR(v.y, 0.0, 1e-14);
    }
    const int pivot2 = c.t2 > c.t1 ? 1 : (c.t2 < c.t1 ? 0 : -1);
    if (pivot2 >= 0) {
      const V2 va = PointVelocity(world.block2(), got2[pivot2]);
      const V2 vb = PointVelocity(world.block1(), got2[pivot2]);
      EXPECT_NEAR(va.x, vb.x, 1e-14);
      EXPECT_NEAR(va.y, vb.y, 1e-14);
    }
    // Nothing out of the plane at the start.
    EXPECT_EQ(world.block1()->getCenterOfMassPosition().z(), 0.0);
    EXPECT_EQ(world.block2()->getCenterOfMassPosition().z(), 0.0);
  }
}

TEST(RockingWorldTest, SingleBlockPlacementAndReadBack) {
  Scene s;
  s.blocks = {{1.0, 4.0, 1.0, 10000.0, 0.0}};
  s.initial.theta_rad[0] = -0.1;
  s.initial.omega_radps[0] = 0.25;
  s.run.duration_s = 0.01;
  const BulletInput input = MakeBulletInput(s, GroundMotion());
  RockingWorld world(input);
  EXPECT_EQ(world.block2(), nullptr);
  const auto want = ChainCorners(s);
  const auto got = BodyCorners(world.block1(), 0.5, 2.0);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(got[k].x, want[0][k].x, 1e-12);
    EXPECT_NEAR(got[k].y, want[0][k].y, 1e-12);
  }
  // Read back in the thesis's convention: theta = -(rotation about +z).
  const StepReadout r = world.Read(0);
  EXPECT_NEAR(-std::atan2(r.blocks[0].sin_phi, r.blocks[0].cos_phi), -0.1, 1e-15);
  EXPECT_NEAR(-r.blocks[0].w_radps, 0.25, 1e-15);
  EXPECT_EQ(r.t_s, 0.0);
}

TEST(RockingWorldTest, BodiesCarryTheSceneSettings) {
  Scene s = ThesisStack(0.0, 0.0, 0.0, 0.0);
  SetEngineSetting(s, "bullet", "friction", 0.7);
  SetEngineSetting(s, "bullet", "restitution", 0.1);
  SetEngineSetting(s, "bullet", "rolling_friction", 0.01);
  SetEngineSetting(s, "bullet", "margin", 0.001);
  SetEngineSetting(s, "bullet", "solver_iterations", std::int64_t{33});
  SetEngineSetting(s, "bullet", "erp", 0.3);
  SetEngineSetting(s, "bullet", "erp2", 0.6);
  SetEngineSetting(s, "bullet", "split_impulse", false);
  SetEngineSetting(s, "bullet", "split_impulse_threshold", -0.01);
  SetEngineSetting(s, "bullet", "restitution_velocity_threshold", 0.05);
  const BulletInput input = MakeBulletInput(s, GroundMotion());
  RockingWorld world(input);
  for (btRigidBody* b : {world.block1(), world.block2(), world.ground()}) {
    EXPECT_DOUBLE_EQ(b->getFriction(), 0.7);
    EXPECT_DOUBLE_EQ(b->getRestitution(), 0.1);
    EXPECT_DOUBLE_EQ(b->getRollingFriction(), 0.01);
    EXPECT_DOUBLE_EQ(b->getCollisionShape()->getMargin(), 0.001);
  }
  for (btRigidBody* b : {world.block1(), world.block2()}) {
    EXPECT_EQ(b->getActivationState(), DISABLE_DEACTIVATION);
    EXPECT_EQ(b->getLinearFactor(), btVector3(1, 1, 0));
    EXPECT_EQ(b->getAngularFactor(), btVector3(0, 0, 1));
  }
  // Box inertia about z: m (B^2 + H^2) / 12, whatever the depth.
  EXPECT_NEAR(1.0 / world.block2()->getInvInertiaDiagLocal().z(), 6250.0 * (1.0 + 6.25) / 12.0,
              1e-9);
  // The margin does not change the box: its half extents with margin are the block's.
  const auto* box = static_cast<const btBoxShape*>(world.block2()->getCollisionShape());
  EXPECT_NEAR(box->getHalfExtentsWithMargin().x(), 0.5, 1e-15);
  EXPECT_NEAR(box->getHalfExtentsWithMargin().y(), 1.25, 1e-15);
  const btContactSolverInfo& si = world.world()->getSolverInfo();
  EXPECT_EQ(si.m_numIterations, 33);
  EXPECT_DOUBLE_EQ(si.m_erp, 0.3);
  EXPECT_DOUBLE_EQ(si.m_erp2, 0.6);
  EXPECT_EQ(si.m_splitImpulse, 0);
  EXPECT_DOUBLE_EQ(si.m_splitImpulsePenetrationThreshold, -0.01);
  EXPECT_DOUBLE_EQ(si.m_restitutionVelocityThreshold, 0.05);
}

TEST(RockingWorldTest, InertialDriveSetsEffectiveGravityBeforeEachStep) {
  Scene s = ThesisStack(0.0, 0.0, 0.0, 0.0);
  s.run.duration_s = 0.003;
  SetEngineSetting(s, "bullet", "time_step", 1e-3);
  GroundMotion m;
  // A ramp 0, 1, 2, 3 m/s^2 at t = 0, 1, 2, 3 ms horizontally, and 0.5 m/s^2 vertically.
  m.set_horizontal(MotionComponent::FromSamples({0.0, 1.0, 2.0, 3.0}, 1e-3, 0.0, "ramp"));
  m.set_vertical(MotionComponent::FromSamples({0.5, 0.5, 0.5, 0.5}, 1e-3, 0.0, "up"));
  const BulletInput input = MakeBulletInput(s, m);
  RockingWorld world(input);
  for (int n = 0; n < 3; ++n) {
    world.ApplyDrive(n);
    const btVector3 g = world.world()->getGravity();
    EXPECT_DOUBLE_EQ(g.x(), -static_cast<double>(n));
    EXPECT_DOUBLE_EQ(g.y(), -(9.81 + 0.5));
    EXPECT_EQ(g.z(), 0.0);
    world.Step();
  }
}

TEST(RockingWorldTest, PlanarConstraintHoldsUnderShaking) {
  // Both components of a strong harmonic; every step's out-of-plane motion is tracked.
  Scene s = ThesisStack(0.05, 0.08, 0.0, 0.0);
  s.run.duration_s = 1.0;
  SetEngineSetting(s, "bullet", "time_step", 1e-3);
  MotionDef h;
  h.key = "base.horizontal";
  h.kind = MotionKind::kHarmonic;
  h.amplitude_g = 0.6;
  h.frequency_hz = 2.0;
  MotionDef v = h;
  v.key = "base.vertical";
  v.amplitude_g = 0.3;
  v.frequency_hz = 3.0;
  s.horizontal = h;
  s.vertical = v;
  const GroundMotion m = GroundMotion::FromScene(s);
  for (const char* drive : {"inertial", "kinematic"}) {
    SetEngineSetting(s, "bullet", "drive", std::string(drive));
    const BulletInput input = MakeBulletInput(s, m);
    RockingWorld world(input);
    double max_z = 0.0, max_tilt = 0.0;
    for (std::int64_t n = 0; n < input.steps; ++n) {
      world.ApplyDrive(n);
      world.Step();
      for (btRigidBody* b : {world.block1(), world.block2()}) {
        const btTransform& t = b->getCenterOfMassTransform();
        max_z = std::max(max_z, std::abs(t.getOrigin().z()));
        max_tilt = std::max({max_tilt, std::abs(t.getBasis()[2][0]), std::abs(t.getBasis()[2][1]),
                             std::abs(t.getBasis()[0][2]), std::abs(t.getBasis()[1][2])});
        max_z = std::max(max_z, std::abs(b->getLinearVelocity().z()));
        max_tilt = std::max({max_tilt, std::abs(b->getAngularVelocity().x()),
                             std::abs(b->getAngularVelocity().y())});
      }
    }
    // Linear factor (1, 1, 0) and angular factor (0, 0, 1) zero every out-of-plane impulse:
    // exactly nothing leaves the plane.
    EXPECT_EQ(max_z, 0.0);
    EXPECT_EQ(max_tilt, 0.0);
  }
}

TEST(RockingWorldTest, KinematicGroundFollowsTheDisplacementWithStepVelocity) {
  Scene s = ThesisStack(0.0, 0.0, 0.0, 0.0);
  s.run.duration_s = 0.01;
  SetEngineSetting(s, "bullet", "time_step", 1e-3);
  SetEngineSetting(s, "bullet", "drive", std::string("kinematic"));
  SetEngineSetting(s, "bullet", "kinematic_highpass_hz", 0.0);
  GroundMotion m;
  m.set_horizontal(MotionComponent::FromSamples({2.0, 2.0}, 1.0, 0.0, "const"));
  const BulletInput input = MakeBulletInput(s, m);
  RockingWorld world(input);
  for (int n = 0; n < 10; ++n) {
    world.ApplyDrive(n);
    world.Step();
    // During step n the ground sits at u_n (collision detection) and moves at
    // (u_{n+1} - u_n) / dt (the solver's ground velocity).
    const double u = input.drive.ux_m[n], u_next = input.drive.ux_m[n + 1];
    EXPECT_NEAR(world.ground()->getCenterOfMassPosition().x(), u, 1e-15);
    EXPECT_NEAR(world.ground()->getLinearVelocity().x(), (u_next - u) / 1e-3, 1e-9);
  }
}

}  // namespace
}  // namespace rockbench::bullet
