#pragma once
/// The Bullet scene of the cylinder (shape "cylinder", issue 41): a btCylinderShapeZ on a ground
/// plane, z up. Compiled into rockbench_bullet only (double precision, in process).
#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>

#include "engines/bullet/bullet_settings.h"
#include "engines/bullet/bullet_world_parts.h"
#include "engines/common/cylinder_world.h"

namespace rockbench::bullet {

/// A Bullet world holding a ground plane z = 0 (a btStaticPlaneShape, static for the inertial
/// drive, kinematic for the kinematic drive) and the cylinder: a btCylinderShapeZ (its axis
/// the body's z) whose contact with the plane is Bullet's convex-plane algorithm, the support
/// point of the exact cylinder (the lowest rim point, one per step, kept in the pair's
/// persistent manifold), with the mass and inertia of CylinderBodyOf set explicitly. World axes
/// are rockbench's cylinder axes (+x horizontal, +y transverse, +z up). Satisfies the
/// CylinderWorld concept (engines/common/cylinder_world.h). Keeps a reference to `input`, which
/// must outlive it.
class BulletCylinderWorld {
 public:
  explicit BulletCylinderWorld(const BulletInput& input);
  ~BulletCylinderWorld();
  BulletCylinderWorld(const BulletCylinderWorld&) = delete;
  BulletCylinderWorld& operator=(const BulletCylinderWorld&) = delete;

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: gravity
  /// (-a_x, -a_y, -(g + a_z)) of CylinderDriveAccel(n). Kinematic drive: the ground at u_n
  /// moving with (u_{n+1} - u_n) / dt during the step.
  void ApplyDrive(std::int64_t n);
  /// One fixed step without interpolation: stepSimulation(dt, 0).
  void Step();
  /// The cylinder's pose after the last step relative to the base (kinematic drive: the
  /// ground's displacement and velocity subtracted).
  CylinderPose ReadPose() const;
  /// Settings in use (ours and the Bullet values they set) for summary.json.
  nlohmann::json Settings() const;

 private:
  btTransform GroundTransform(const Vec3d& u_m) const;

  const BulletInput& in_;
  const CylinderBodyDef body_;
  double dt_ = 0.0;
  bool kinematic_ = false;
  std::int64_t steps_done_ = 0;  // steps taken: the pose is at t = steps_done_ * dt
  std::int64_t next_step_ = 0;   // the step ApplyDrive set up
  double cylinder_friction_ = 0.0, ground_friction_ = 0.0;
  BulletDynamics dynamics_;
  btDiscreteDynamicsWorld* const world_;  // dynamics_'s
  std::unique_ptr<btStaticPlaneShape> ground_shape_;
  std::unique_ptr<btCylinderShapeZ> shape_;
  std::unique_ptr<btRigidBody> ground_;
  std::unique_ptr<btRigidBody> cylinder_;
};

}  // namespace rockbench::bullet
