#pragma once
/// The DART scene of the cylinder (shape "cylinder", issue 41): a free body on a ground box,
/// z up, with DART 6.12's boxed-LCP contacts and the collision detector of the [dart] settings.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>

#include "engines/common/cylinder_world.h"
#include "engines/dart/dart_settings.h"

namespace rockbench::dart_engine {

/// Sides of the prism that stands for the cylinder with DART's own collision detector, which
/// has no cylinder: the regular polygon inscribed in the rim (its vertices on the circle), 64
/// sides, whose edges lie at most R (1 - cos(pi / 64)) = 1.2e-3 R = 6.0e-4 D inside the rim.
inline constexpr int kDartCylinderPrismSides = 64;

/// Sides of the mesh FCL makes of DART's CylinderShape (DART 6.12's FCLCollisionDetector meshes
/// every cylinder with 16 slices, whatever its primitive-shape setting).
inline constexpr int kDartFclCylinderSlices = 16;

/// A DART world holding a ground box (top face z = 0 in the base frame; an immobile skeleton on
/// a 3-D translational joint, moved by hand for the kinematic drive) and the cylinder, a free
/// body with the mass and inertia of CylinderBodyOf set explicitly, its collision shape:
/// - collision "dart" (DART's own detector, ODE's box-box): the prism of
///   kDartCylinderPrismSides sides, as kDartCylinderPrismSides / 4 thin boxes through the axis
///   whose corners are the prism's vertices (a plane meets a union of boxes where it meets
///   their convex hull, the prism: each contact is a vertex, an edge's two ends or a face's
///   corners, exactly);
/// - collision "fcl": DART's CylinderShape, which FCL meshes (kDartFclCylinderSlices sides).
/// World axes are rockbench's cylinder axes (+x horizontal, +y transverse, +z up). Satisfies
/// the CylinderWorld concept (engines/common/cylinder_world.h). Keeps a reference to `input`,
/// which must outlive it. Takes DART's process-wide contact parameters as DartWorld does
/// (std::invalid_argument when another live DART world uses other values).
class DartCylinderWorld {
 public:
  DartCylinderWorld(const EngineInput& input, const DartSettings& settings);
  ~DartCylinderWorld();
  DartCylinderWorld(const DartCylinderWorld&) = delete;
  DartCylinderWorld& operator=(const DartCylinderWorld&) = delete;

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: gravity
  /// (-a_x, -a_y, -(g + a_z)) of CylinderDriveAccel(n). Kinematic drive: the ground at u_n
  /// moving with (u_{n+1} - u_n) / dt during the step.
  void ApplyDrive(std::int64_t n);
  /// One fixed step (World::step: semi-implicit Euler, contacts by one boxed LCP on velocities).
  void Step();
  /// The cylinder's pose after the last step relative to the base (kinematic drive: the
  /// ground's displacement and the velocity it moved with in that step subtracted).
  CylinderPose ReadPose() const;
  /// Settings in use (ours and the DART values they set) for summary.json.
  nlohmann::json Settings() const;
  /// Counts since construction, for summary.json (DartWorld::Diagnostics' keys).
  nlohmann::json Diagnostics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::dart_engine
