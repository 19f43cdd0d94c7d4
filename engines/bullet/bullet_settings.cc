#include "engines/bullet/bullet_settings.h"

#include <algorithm>
#include <utility>

#include "scene/scene.h"

namespace rockbench::bullet {

namespace {

// "double" or "float": btScalar.
const char* PrecisionName(BulletPrecision p) {
  return p == BulletPrecision::kFloat ? "float" : "double";
}

// The [bullet] table: each key once, bound to the BulletConfig member it sets.
const SettingsTable<BulletConfig>& BulletTable() {
  using R = SettingRange;
  using S = BulletConfig;
  static const SettingsTable<S> kTable = [] {
    SettingsTable<S> t("bullet");
    AddTimeStepSetting(
        t.unbound(), "1/60 s",
        "fixed step; Bullet's 1/60 s misses every impact of the stack (docs/stress.md)");
    t.Integer("solver_iterations", &S::solver_iterations, 1, 100000, "10",
              "sequential-impulse iterations; 10 leaves the stack's contacts unconverged");
    t.Choice("precision", &S::precision, {BulletPrecision::kDouble, BulletPrecision::kFloat},
             PrecisionName, "float (libbullet-dev)",
             "btScalar: double in process (bullet-float64), float in a helper program");
    AddDriveSetting(t.unbound());
    t.Number("erp", &S::erp, R::kUnitInterval, "", "0.2",
             "joint error reduction (contacts use erp2); 0: no position correction");
    t.Number("erp2", &S::erp2, R::kUnitInterval, "", "0.2",
             "contact penetration recovery through split impulse; 0: none (SimBenchmark's "
             "setting)");
    t.Flag("split_impulse", &S::split_impulse, "true", "position correction apart from velocities");
    t.Number("split_impulse_threshold", &S::split_impulse_threshold, R::kFinite, "m", "-0.04 m",
             "penetration below which split impulse is used; -0.04 throws the blocks up");
    t.Number("restitution", &S::restitution, R::kUnitInterval, "", "0",
             "per body; the impact loses energy by the geometry, as in the model");
    t.Number("friction", &S::friction, R::kNonNegative, "", "0.5",
             "per body (combined f*f, clamped at 10): the model assumes no sliding");
    t.Number("rolling_friction", &S::rolling_friction, R::kNonNegative, "", "0", "per body");
    t.Number("restitution_velocity_threshold", &S::restitution_velocity_threshold, R::kNonNegative,
             "m/s", "0.2 m/s", "no restitution below this approach speed");
    t.Number("margin", &S::margin_m, R::kNonNegative, "m", "0.04 m",
             "collision margin; a margin rounds the corners the blocks pivot on");
    t.Number("ground_depth", &S::ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(t.unbound());
    return t;
  }();
  return kTable;
}

}  // namespace

const EngineSettingsSchema& BulletSettingsSchema() {
  return BulletTable().schema();
}

BulletInput MakeBulletInput(const Scene& scene, const GroundMotion& motion,
                            double stop_at_rest_after_s) {
  EngineRunInput<BulletConfig> run =
      MakeEngineRunInput(scene, motion, BulletTable(), stop_at_rest_after_s);
  BulletInput in;
  static_cast<EngineInput&>(in) = std::move(run.input);
  in.config = run.settings;
  return in;
}

double BulletCombinedFriction(double per_body_friction) {
  return std::min(per_body_friction * per_body_friction, 10.0);
}

}  // namespace rockbench::bullet
