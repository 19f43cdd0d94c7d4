#pragma once
/// The Bullet scene of the stack of N blocks. This file and rocking_world.cc / bullet_engine.cc
/// are compiled twice: against bullet-float64 (BT_USE_DOUBLE_PRECISION, library
/// rockbench_bullet) and against bullet (single precision, library rockbench_bullet_float, only
/// linked into the helper program rockbench-bullet-float). The two never meet in one binary.
#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "engine/engine.h"
#include "engines/bullet/bullet_engine.h"
#include "engines/bullet/bullet_settings.h"
#include "engines/bullet/bullet_world_parts.h"
#include "engines/common/monitor.h"

namespace rockbench::bullet {

/// A Bullet world holding a static (inertial drive) or kinematic (kinematic drive) ground box
/// and N btBoxShape blocks placed by the pivot chain (scene/stack_pose.h), added bottom first.
/// Contacts are only between neighbours: block 1 and the ground, block k and block k + 1. With
/// three or more blocks a broadphase filter (NeighbourFilter in rocking_world.cc) keeps every
/// other pair out of the collision pipeline; one and two blocks have no filter (their only
/// other pair, block 2 and the ground, never meets before an overturn ends the run), as before
/// issue 23. Keeps a reference to `input`, which must outlive it.
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

  btDiscreteDynamicsWorld* world() { return world_; }
  /// Block k's body (k = 0: block 1, the lowest), bottom first.
  btRigidBody* block(int k) { return blocks_.at(static_cast<size_t>(k)).get(); }
  int block_count() const { return static_cast<int>(blocks_.size()); }
  btRigidBody* block1() { return blocks_[0].get(); }
  btRigidBody* block2() {
    return blocks_.size() >= 2 ? blocks_[1].get() : nullptr;
  }  ///< null for a single block
  btRigidBody* ground() { return ground_.get(); }

 private:
  btTransform GroundTransform(double ux_m, double uy_m) const;

  const BulletInput& in_;
  double dt_ = 0.0;
  bool kinematic_ = false;
  // Three or more blocks only; declared first so that it outlives the broadphase's pair cache.
  std::unique_ptr<btOverlapFilterCallback> filter_;
  BulletDynamics dynamics_;
  btDiscreteDynamicsWorld* const world_;  // dynamics_'s
  std::unique_ptr<btBoxShape> ground_shape_;
  std::vector<std::unique_ptr<btBoxShape>> shapes_;  // per block, bottom first
  std::unique_ptr<btRigidBody> ground_;
  std::vector<std::unique_ptr<btRigidBody>> blocks_;  // per block, bottom first
  double ground_half_depth_m_ = 0.0;
  std::vector<double> z_;  // initial out-of-plane positions, per block
  // Per block, the scene's friction with its support (infinite: Bullet's own combination); each
  // block's user pointer points at its entry. Empty when every block's is infinite.
  std::vector<double> base_friction_;
};

}  // namespace rockbench::bullet
