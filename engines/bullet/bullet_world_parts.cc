#include "engines/bullet/bullet_world_parts.h"

#include <algorithm>
#include <cmath>

#include "engines/bullet/bullet_engine.h"

namespace rockbench::bullet {

BulletDynamics::BulletDynamics(const BulletInput& input, const btVector3& gravity_mps2) {
  const BulletConfig& c = input.config;
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
  si.m_timeStep = btScalar(input.time_step_s);
  world_->setGravity(gravity_mps2);
}

btRigidBody::btRigidBodyConstructionInfo BodyInfo(const BulletConfig& config, double mass_kg,
                                                  btCollisionShape* shape,
                                                  const btVector3& inertia_kgm2,
                                                  const btTransform& start, double friction) {
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass_kg), nullptr, shape, inertia_kgm2);
  info.m_startWorldTransform = start;
  info.m_friction = btScalar(friction);
  info.m_restitution = btScalar(config.restitution);
  info.m_rollingFriction = btScalar(config.rolling_friction);
  info.m_linearDamping = 0;
  info.m_angularDamping = 0;
  return info;
}

std::unique_ptr<btRigidBody> MakeGround(const BulletInput& input, btCollisionShape* shape,
                                        const btTransform& start, double friction) {
  auto ground = std::make_unique<btRigidBody>(
      BodyInfo(input.config, 0.0, shape, btVector3(0, 0, 0), start, friction));
  if (input.drive_kind == DriveKind::kKinematic) {
    // A mass-0 body is flagged static; a kinematic body must not be (a BT_THREADSAFE solver
    // maps static bodies to a fixed solver body with zero velocity).
    ground->setCollisionFlags((ground->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT) |
                              btCollisionObject::CF_KINEMATIC_OBJECT);
    ground->setActivationState(DISABLE_DEACTIVATION);
  }
  return ground;
}

void PlaceKinematicGround(btRigidBody* ground, const btTransform& at_step,
                          const btTransform& step_behind) {
  ground->setWorldTransform(at_step);
  ground->setInterpolationWorldTransform(step_behind);
}

nlohmann::json CommonSettings(const BulletInput& input, const btDiscreteDynamicsWorld& world) {
  const BulletConfig& c = input.config;
  const btContactSolverInfo& si = world.getSolverInfo();
  const double dt = input.time_step_s;
  nlohmann::json j;
  j["precision"] = CompiledPrecision();
  j["drive"] = input.drive_kind == DriveKind::kKinematic ? "kinematic" : "inertial";
  j["time_step_s"] = input.time_step_s;
  j["output_interval_s"] = input.run.output_interval_s;
  j["substeps_per_sample"] = std::max(1.0, std::round(input.run.output_interval_s / dt));
  j["solver_iterations"] = c.solver_iterations;
  j["erp"] = c.erp;
  j["erp2"] = c.erp2;
  j["split_impulse"] = c.split_impulse;
  j["split_impulse_threshold"] = c.split_impulse_threshold;
  j["restitution"] = c.restitution;
  // Bullet multiplies the two bodies' restitutions.
  j["restitution_combined"] = c.restitution * c.restitution;
  j["friction"] = c.friction;
  j["rolling_friction"] = c.rolling_friction;
  j["restitution_velocity_threshold"] = c.restitution_velocity_threshold;
  j["margin_m"] = c.margin_m;
  j["kinematic_highpass_hz"] = input.kinematic_highpass_hz;
  j["deactivation"] = "disabled";
  j["warmstarting_factor"] = double(si.m_warmstartingFactor);
  j["solver_mode"] = si.m_solverMode;
  j["bullet_version"] = btGetVersion();
  return j;
}

}  // namespace rockbench::bullet
