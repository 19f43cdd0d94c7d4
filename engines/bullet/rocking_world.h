#pragma once
/// The Bullet scene of the two stacked blocks. This file and rocking_world.cc / bullet_engine.cc
/// are compiled twice: against bullet-float64 (BT_USE_DOUBLE_PRECISION, library
/// rockbench_bullet) and against bullet (single precision, library rockbench_bullet_float, only
/// linked into the helper program rockbench-bullet-float). The two never meet in one binary.
#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>

#include "engines/bullet/bullet_engine.h"
#include "engines/bullet/bullet_settings.h"
#include "engines/common/monitor.h"
#include "scene/engine.h"

namespace rockbench::bullet {

/// A Bullet world holding a static (inertial drive) or kinematic (kinematic drive) ground box
/// and one or two btBoxShape blocks placed by the pivot chain. Keeps a reference to `input`,
/// which must outlive it.
class RockingWorld {
 public:
  explicit RockingWorld(const BulletInput& input);
  ~RockingWorld();
  RockingWorld(const RockingWorld&) = delete;
  RockingWorld& operator=(const RockingWorld&) = delete;

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: gravity
  /// (-xg''(t_n), -(g + yg''(t_n)), 0). Kinematic drive: the ground at u(t_n) moving with
  /// (u_{n+1} - u_n) / dt during the step.
  void ApplyDrive(std::int64_t n);
  /// One fixed step without interpolation: stepSimulation(dt, 0).
  void Step();
  /// The state after n steps, read from the rigid bodies' centre-of-mass transforms.
  StepReadout Read(std::int64_t n) const;

  /// Settings in use (ours and the Bullet values they set) for summary.json.
  nlohmann::json Settings() const;

  btDiscreteDynamicsWorld* world() { return world_.get(); }
  btRigidBody* block1() { return block1_.get(); }
  btRigidBody* block2() { return block2_.get(); }  ///< null for a single block
  btRigidBody* ground() { return ground_.get(); }

 private:
  btTransform GroundTransform(double ux_m, double uy_m) const;

  const BulletInput& in_;
  double dt_ = 0.0;
  bool kinematic_ = false;
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::unique_ptr<btBoxShape> ground_shape_, shape1_, shape2_;
  std::unique_ptr<btRigidBody> ground_, block1_, block2_;
  double ground_half_depth_m_ = 0.0;
  double z1_ = 0.0, z2_ = 0.0;  // initial out-of-plane positions
};

}  // namespace rockbench::bullet
