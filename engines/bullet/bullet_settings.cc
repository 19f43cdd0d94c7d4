#include "engines/bullet/bullet_settings.h"

#include <algorithm>

#include "scene/scene.h"

namespace rockbench::bullet {

const EngineSettingsSchema& BulletSettingsSchema() {
  using R = SettingRange;
  static const EngineSettingsSchema kSchema = [] {
    EngineSettingsSchema s;
    s.engine = "bullet";
    const BulletConfig d;
    AddTimeStepSetting(
        s, "1/60 s",
        "fixed step; Bullet's 1/60 s misses every impact of the stack (docs/stress.md)");
    s.Integer("solver_iterations", d.solver_iterations, 1, 100000, "10",
              "sequential-impulse iterations; 10 leaves the stack's contacts unconverged");
    s.Choice("precision", "double", {"double", "float"}, "float (libbullet-dev)",
             "btScalar: double in process (bullet-float64), float in a helper program");
    AddDriveSetting(s);
    s.Number("erp", d.erp, R::kUnitInterval, "", "0.2",
             "joint error reduction (contacts use erp2); 0: no position correction");
    s.Number("erp2", d.erp2, R::kUnitInterval, "", "0.2",
             "contact penetration recovery through split impulse; 0: none (SimBenchmark's "
             "setting)");
    s.Flag("split_impulse", d.split_impulse, "true", "position correction apart from velocities");
    s.Number("split_impulse_threshold", d.split_impulse_threshold, R::kFinite, "m", "-0.04 m",
             "penetration below which split impulse is used; -0.04 throws the blocks up");
    s.Number("restitution", d.restitution, R::kUnitInterval, "", "0",
             "per body; the impact loses energy by the geometry, as in the model");
    s.Number("friction", d.friction, R::kNonNegative, "", "0.5",
             "per body (combined f*f, clamped at 10): the model assumes no sliding");
    s.Number("rolling_friction", d.rolling_friction, R::kNonNegative, "", "0", "per body");
    s.Number("restitution_velocity_threshold", d.restitution_velocity_threshold, R::kNonNegative,
             "m/s", "0.2 m/s", "no restitution below this approach speed");
    s.Number("margin", d.margin_m, R::kNonNegative, "m", "0.04 m",
             "collision margin; a margin rounds the corners the blocks pivot on");
    s.Number("ground_depth", d.ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(s);
    return s;
  }();
  return kSchema;
}

BulletInput MakeBulletInput(const Scene& scene, const GroundMotion& motion,
                            double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, BulletSettingsSchema());
  BulletInput in;
  static_cast<EngineInput&>(in) =
      MakeEngineInput(scene, motion, "bullet", set, stop_at_rest_after_s);
  BulletConfig& c = in.config;
  c.solver_iterations = static_cast<int>(set.Integer("solver_iterations"));
  c.precision =
      set.Choice("precision") == "float" ? BulletPrecision::kFloat : BulletPrecision::kDouble;
  c.erp = set.Number("erp");
  c.erp2 = set.Number("erp2");
  c.split_impulse = set.Flag("split_impulse");
  c.split_impulse_threshold = set.Number("split_impulse_threshold");
  c.restitution = set.Number("restitution");
  c.friction = set.Number("friction");
  c.rolling_friction = set.Number("rolling_friction");
  c.restitution_velocity_threshold = set.Number("restitution_velocity_threshold");
  c.margin_m = set.Number("margin");
  c.ground_depth_m = set.Number("ground_depth");
  return in;
}

double BulletCombinedFriction(double per_body_friction) {
  return std::min(per_body_friction * per_body_friction, 10.0);
}

}  // namespace rockbench::bullet
