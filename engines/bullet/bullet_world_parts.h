#pragma once
/// What the Bullet worlds share, whatever they hold (the planar stack, RockingWorld in
/// rocking_world.h; the cylinder, BulletCylinderWorld in cylinder_world.h): the dynamics world
/// with the [bullet] solver settings, a body's contact coefficients, the ground as a static or
/// kinematic body, the kinematic ground's placement for a step, and the settings both write to
/// summary.json. Compiled with RockingWorld in both precisions (rockbench_bullet and
/// rockbench_bullet_float).
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "engines/bullet/bullet_settings.h"

namespace rockbench::bullet {

/// A btDiscreteDynamicsWorld (default collision configuration and dispatcher, DBVT broadphase,
/// sequential-impulse solver) whose solver info has the [bullet] table's solver_iterations,
/// erp, erp2, split_impulse, split_impulse_threshold and restitution_velocity_threshold and the
/// input's time step, and whose gravity is `gravity_mps2` (m/s^2) until the drive sets it.
class BulletDynamics {
 public:
  BulletDynamics(const BulletInput& input, const btVector3& gravity_mps2);
  BulletDynamics(const BulletDynamics&) = delete;
  BulletDynamics& operator=(const BulletDynamics&) = delete;

  btDiscreteDynamicsWorld* world() const { return world_.get(); }

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
};

/// A body's construction info: mass `mass_kg` (0: not dynamic), `shape` with the local inertia
/// `inertia_kgm2`, at `start`, with the friction `friction` (Bullet multiplies two bodies'
/// values), the table's restitution and rolling friction, and no damping.
btRigidBody::btRigidBodyConstructionInfo BodyInfo(const BulletConfig& config, double mass_kg,
                                                  btCollisionShape* shape,
                                                  const btVector3& inertia_kgm2,
                                                  const btTransform& start, double friction);

/// The ground: a body of mass 0 of `shape` at `start` with the friction `friction`, static for
/// the inertial drive, kinematic (and never deactivated) for the kinematic drive. Not yet added
/// to the world.
std::unique_ptr<btRigidBody> MakeGround(const BulletInput& input, btCollisionShape* shape,
                                        const btTransform& start, double friction);

/// The kinematic ground for a step: at `at_step` (u_n) and, as its interpolation transform,
/// at `step_behind` (2 u_n - u_{n+1}). Bullet sets a kinematic body's velocity to (world -
/// interpolation) / dt in stepSimulation, so the ground moves with (u_{n+1} - u_n) / dt while
/// collision detection sees it at u_n, where the bodies are.
void PlaceKinematicGround(btRigidBody* ground, const btTransform& at_step,
                          const btTransform& step_behind);

/// The settings both worlds write to summary.json: precision, drive, steps, the solver's keys
/// and the Bullet values they set, the contact coefficients of the table, margin, kinematic
/// high-pass, deactivation and Bullet's version.
nlohmann::json CommonSettings(const BulletInput& input, const btDiscreteDynamicsWorld& world);

}  // namespace rockbench::bullet
