#include "engines/bullet/rocking_world.h"

#include <algorithm>
#include <cmath>

#include "scene/stack_pose.h"

namespace rockbench::bullet {
namespace {

btTransform PoseTransform(const PlanarPose& p, double ux, double uy, double z) {
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(btScalar(p.x_m + ux), btScalar(p.y_m + uy), btScalar(z)));
  t.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(p.phi_rad)));
  return t;
}

void ReadBody(const btRigidBody& body, BodyReadout* out) {
  const btTransform& t = body.getCenterOfMassTransform();
  const btMatrix3x3& r = t.getBasis();
  out->x_m = double(t.getOrigin().x());
  out->y_m = double(t.getOrigin().y());
  out->cos_phi = double(r[0][0]);
  out->sin_phi = double(r[1][0]);
  out->vx_mps = double(body.getLinearVelocity().x());
  out->vy_mps = double(body.getLinearVelocity().y());
  out->w_radps = double(body.getAngularVelocity().z());
}

// Largest out-of-plane rotation component of a basis (0 for a rotation about z alone).
double OutOfPlaneRotation(const btMatrix3x3& r) {
  return std::max({std::abs(double(r[2][0])), std::abs(double(r[2][1])), std::abs(double(r[0][2])),
                   std::abs(double(r[1][2]))});
}

}  // namespace

const char* CompiledPrecision() {
  return sizeof(btScalar) == sizeof(double) ? "double" : "float";
}

RockingWorld::RockingWorld(const BulletInput& input) : in_(input) {
  const BulletConfig& c = in_.config;
  dt_ = in_.time_step_s;
  kinematic_ = in_.drive_kind == DriveKind::kKinematic;

  collision_config_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(collision_config_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                     solver_.get(), collision_config_.get());
  btContactSolverInfo& si = world_->getSolverInfo();
  si.m_numIterations = c.solver_iterations;
  si.m_erp = btScalar(c.erp);
  si.m_erp2 = btScalar(c.erp2);
  si.m_splitImpulse = c.split_impulse ? 1 : 0;
  si.m_splitImpulsePenetrationThreshold = btScalar(c.split_impulse_threshold);
  si.m_restitutionVelocityThreshold = btScalar(c.restitution_velocity_threshold);
  si.m_timeStep = btScalar(dt_);
  world_->setGravity(btVector3(0, btScalar(-in_.run.gravity_mps2), 0));

  const double b1 = 0.5 * in_.block1.width_m, h1 = 0.5 * in_.block1.height_m;
  const double b2 = in_.block2 ? 0.5 * in_.block2->width_m : 0.0;
  const double h2 = in_.block2 ? 0.5 * in_.block2->height_m : 0.0;
  const double d1 = in_.block1.depth_m, d2 = in_.block2 ? in_.block2->depth_m : 0.0;

  // Ground: a box whose top face is y = 0 in the base frame, much wider than the stack.
  const double size = std::max({b1, h1, b2, h2, 0.5});
  ground_half_depth_m_ = 0.5 * c.ground_depth_m;
  ground_shape_ = std::make_unique<btBoxShape>(btVector3(
      btScalar(40.0 * size), btScalar(ground_half_depth_m_), btScalar(std::max(d1, d2) + 1.0)));
  ground_shape_->setMargin(btScalar(c.margin_m));
  const double ux0 = kinematic_ ? in_.drive.ux_m.front() : 0.0;
  const double uy0 = kinematic_ ? in_.drive.uy_m.front() : 0.0;
  {
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, ground_shape_.get(),
                                                  btVector3(0, 0, 0));
    info.m_startWorldTransform = GroundTransform(ux0, uy0);
    info.m_friction = btScalar(c.friction);
    info.m_restitution = btScalar(c.restitution);
    info.m_rollingFriction = btScalar(c.rolling_friction);
    ground_ = std::make_unique<btRigidBody>(info);
    if (kinematic_) {
      // A mass-0 body is flagged static; a kinematic body must not be (a BT_THREADSAFE solver
      // maps static bodies to a fixed solver body with zero velocity).
      ground_->setCollisionFlags(
          (ground_->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT) |
          btCollisionObject::CF_KINEMATIC_OBJECT);
      ground_->setActivationState(DISABLE_DEACTIVATION);
    }
    world_->addRigidBody(ground_.get());
  }

  // Blocks, placed by the pivot chain in the base frame then shifted with the ground.
  const StackPlacement place = PlaceStack(b1, h1, b2, h2, in_.two_blocks(), in_.initial);
  const double gvx = kinematic_ ? in_.drive.ux0_mps : 0.0;
  const double gvy = kinematic_ ? in_.drive.uy0_mps : 0.0;
  auto make_block = [&](const BlockDef& def, const PlanarPose& pose, double z,
                        std::unique_ptr<btBoxShape>* shape) {
    *shape = std::make_unique<btBoxShape>(btVector3(
        btScalar(0.5 * def.width_m), btScalar(0.5 * def.height_m), btScalar(0.5 * def.depth_m)));
    (*shape)->setMargin(btScalar(c.margin_m));
    btVector3 inertia(0, 0, 0);
    (*shape)->calculateLocalInertia(btScalar(def.mass_kg), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(def.mass_kg), nullptr, shape->get(),
                                                  inertia);
    info.m_startWorldTransform = PoseTransform(pose, ux0, uy0, z);
    info.m_friction = btScalar(c.friction);
    info.m_restitution = btScalar(c.restitution);
    info.m_rollingFriction = btScalar(c.rolling_friction);
    info.m_linearDamping = 0;
    info.m_angularDamping = 0;
    auto body = std::make_unique<btRigidBody>(info);
    // Planar motion: translation in x-y, rotation about z only.
    body->setLinearFactor(btVector3(1, 1, 0));
    body->setAngularFactor(btVector3(0, 0, 1));
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setLinearVelocity(btVector3(btScalar(pose.vx_mps + gvx), btScalar(pose.vy_mps + gvy), 0));
    body->setAngularVelocity(btVector3(0, 0, btScalar(pose.w_radps)));
    world_->addRigidBody(body.get());
    return body;
  };
  z1_ = 0.0;
  block1_ = make_block(in_.block1, place.block1, z1_, &shape1_);
  if (in_.block2) {
    z2_ = 0.0;
    block2_ = make_block(*in_.block2, place.block2, z2_, &shape2_);
  }
}

RockingWorld::~RockingWorld() {
  if (block2_) world_->removeRigidBody(block2_.get());
  if (block1_) world_->removeRigidBody(block1_.get());
  if (ground_) world_->removeRigidBody(ground_.get());
}

btTransform RockingWorld::GroundTransform(double ux, double uy) const {
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(btScalar(ux), btScalar(uy - ground_half_depth_m_), 0));
  return t;
}

void RockingWorld::ApplyDrive(std::int64_t n) {
  const size_t i = static_cast<size_t>(n);
  if (!kinematic_) {
    const double ax = in_.drive.ax_mps2.empty() ? 0.0 : in_.drive.ax_mps2[i];
    const double ay = in_.drive.ay_mps2.empty() ? 0.0 : in_.drive.ay_mps2[i];
    // The exact equivalent of a translating base: effective gravity in the base frame.
    world_->setGravity(btVector3(btScalar(-ax), btScalar(-(in_.run.gravity_mps2 + ay)), 0));
    return;
  }
  // Kinematic: Bullet sets a kinematic body's velocity to (world - interpolation) / dt in
  // stepSimulation; placing the interpolation pose one step behind makes that velocity
  // (u_{n+1} - u_n) / dt while collision detection sees the ground at u_n, where the blocks are.
  const double ux = in_.drive.ux_m[i], uy = in_.drive.uy_m[i];
  const double nx = in_.drive.ux_m[i + 1], ny = in_.drive.uy_m[i + 1];
  ground_->setWorldTransform(GroundTransform(ux, uy));
  ground_->setInterpolationWorldTransform(GroundTransform(2.0 * ux - nx, 2.0 * uy - ny));
}

void RockingWorld::Step() {
  world_->stepSimulation(btScalar(dt_), 0);
}

StepReadout RockingWorld::Read(std::int64_t n) const {
  StepReadout s;
  s.t_s = static_cast<double>(n) * dt_;
  ReadBody(*block1_, &s.block1);
  double oop_m = std::abs(double(block1_->getCenterOfMassTransform().getOrigin().z()) - z1_);
  double oop_rad = OutOfPlaneRotation(block1_->getCenterOfMassTransform().getBasis());
  if (block2_) {
    ReadBody(*block2_, &s.block2);
    oop_m = std::max(oop_m,
                     std::abs(double(block2_->getCenterOfMassTransform().getOrigin().z()) - z2_));
    oop_rad = std::max(oop_rad, OutOfPlaneRotation(block2_->getCenterOfMassTransform().getBasis()));
  }
  s.out_of_plane_m = oop_m;
  s.out_of_plane_rad = oop_rad;
  ReadBaseMotion(in_, n, &s);
  return s;
}

nlohmann::json RockingWorld::Settings() const {
  const BulletConfig& c = in_.config;
  const btContactSolverInfo& si = world_->getSolverInfo();
  nlohmann::json j;
  j["precision"] = CompiledPrecision();
  j["drive"] = kinematic_ ? "kinematic" : "inertial";
  j["time_step_s"] = in_.time_step_s;
  j["output_interval_s"] = in_.run.output_interval_s;
  j["substeps_per_sample"] = std::max(1.0, std::round(in_.run.output_interval_s / dt_));
  j["solver_iterations"] = c.solver_iterations;
  j["erp"] = c.erp;
  j["erp2"] = c.erp2;
  j["split_impulse"] = c.split_impulse;
  j["split_impulse_threshold"] = c.split_impulse_threshold;
  j["restitution"] = c.restitution;
  j["friction"] = c.friction;
  // Bullet multiplies the two bodies' values; friction products are clamped at 10.
  j["friction_combined"] = std::min(10.0, c.friction * c.friction);
  j["restitution_combined"] = c.restitution * c.restitution;
  j["rolling_friction"] = c.rolling_friction;
  j["restitution_velocity_threshold"] = c.restitution_velocity_threshold;
  j["margin_m"] = c.margin_m;
  j["ground_depth_m"] = c.ground_depth_m;
  j["kinematic_highpass_hz"] = in_.kinematic_highpass_hz;
  j["deactivation"] = "disabled";
  j["warmstarting_factor"] = double(si.m_warmstartingFactor);
  j["solver_mode"] = si.m_solverMode;
  j["bullet_version"] = btGetVersion();
  return j;
}

}  // namespace rockbench::bullet
