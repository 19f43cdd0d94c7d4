#pragma once
/// Bullet's settings: the scene's [bullet] table (schema, our defaults beside Bullet's), and the
/// input of one Bullet run (the common engine input plus these settings). Free of Bullet
/// headers: the same input drives the double engine in process and the float helper program.
#include <limits>

#include "engines/common/engine_input.h"
#include "scene/engine_settings.h"

namespace rockbench::bullet {

enum class BulletPrecision { kDouble, kFloat };

/// Settings of the Bullet engine ([bullet] table). Defaults are ours; Bullet's are in the schema
/// (BulletSettingsSchema) and docs/engines.md. The time step, drive and kinematic baseline
/// corner are in EngineInput.
struct BulletConfig {
  int solver_iterations = 50;  ///< sequential-impulse iterations (Bullet default 10)
  BulletPrecision precision = BulletPrecision::kDouble;
  double erp = 0.2;           ///< joint ERP (Bullet default 0.2; contacts use erp2)
  double erp2 = 0.8;          ///< contact penetration recovery (Bullet 3.24 default 0.2)
  bool split_impulse = true;  ///< Bullet default true
  /// m; Bullet's default -0.04 corrects shallow penetration with a velocity bias that throws
  /// the blocks up at every impact (docs/bullet.md): ours is 0, all through split impulse.
  double split_impulse_threshold = 0.0;
  double restitution = 0.0;       ///< per body; Bullet multiplies the two bodies' values
  double friction = 3.0;          ///< per body; Bullet multiplies and clamps the product at 10
  double rolling_friction = 0.0;  ///< per body
  double restitution_velocity_threshold = 0.2;  ///< m/s (Bullet default 0.2)
  double margin_m = 0.0;        ///< collision margin, m (Bullet default 0.04 for boxes)
  double ground_depth_m = 1.0;  ///< ground box thickness, m

  bool operator==(const BulletConfig&) const = default;
};

/// One Bullet run's input.
struct BulletInput : EngineInput {
  BulletConfig config;
};

/// The keys of [bullet].
const EngineSettingsSchema& BulletSettingsSchema();

/// Builds a run's input from the scene's resolved [bullet] settings (throws SceneError).
BulletInput MakeBulletInput(const Scene& scene, const GroundMotion& motion,
                            double stop_at_rest_after_s = std::numeric_limits<double>::infinity());

/// Bullet's friction coefficient between two bodies of per-body friction f: f * f, clamped at
/// 10 (btManifoldResult::calculateCombinedFriction; docs/bullet.md).
double BulletCombinedFriction(double per_body_friction);

}  // namespace rockbench::bullet
