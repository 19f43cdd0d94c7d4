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
    const auto number = [&](const char* key, double v, R range, const char* unit,
                            const char* bullet_default, const char* doc) {
      SettingDef def;
      def.key = key, def.default_value = v, def.range = range, def.unit = unit;
      def.engine_default = bullet_default, def.doc = doc;
      s.settings.push_back(def);
    };
    number("time_step", 1e-4, R::kPositive, "s", "1/60 s",
           "fixed step; Bullet's 1/60 s misses every impact of the stack (docs/stress.md)");
    SettingDef it;
    it.key = "solver_iterations", it.default_value = std::int64_t{d.solver_iterations};
    it.min_integer = 1, it.max_integer = 100000, it.engine_default = "10";
    it.doc = "sequential-impulse iterations; 10 leaves the stack's contacts unconverged";
    s.settings.push_back(it);
    SettingDef prec;
    prec.key = "precision", prec.default_value = std::string("double");
    prec.choices = {"double", "float"}, prec.engine_default = "float (libbullet-dev)";
    prec.doc = "btScalar: double in process (bullet-float64), float in a helper program";
    s.settings.push_back(prec);
    SettingDef drive;
    drive.key = "drive", drive.default_value = std::string("inertial");
    drive.choices = {"inertial", "kinematic"}, drive.engine_default = "-";
    drive.doc = "base motion as tilted gravity (inertial) or a moving ground (kinematic)";
    s.settings.push_back(drive);
    number("erp", d.erp, R::kFraction, "", "0.2", "joint error reduction (contacts use erp2)");
    number("erp2", d.erp2, R::kFraction, "", "0.2",
           "contact penetration recovery through split impulse");
    SettingDef split;
    split.key = "split_impulse", split.default_value = d.split_impulse;
    split.engine_default = "true", split.doc = "position correction apart from velocities";
    s.settings.push_back(split);
    number("split_impulse_threshold", d.split_impulse_threshold, R::kFinite, "m", "-0.04 m",
           "penetration below which split impulse is used; -0.04 throws the blocks up");
    number("restitution", d.restitution, R::kUnitInterval, "", "0",
           "per body; the impact loses energy by the geometry, as in the model");
    number("friction", d.friction, R::kNonNegative, "", "0.5",
           "per body (combined f*f, clamped at 10): the model assumes no sliding");
    number("rolling_friction", d.rolling_friction, R::kNonNegative, "", "0", "per body");
    number("restitution_velocity_threshold", d.restitution_velocity_threshold, R::kNonNegative,
           "m/s", "0.2 m/s", "no restitution below this approach speed");
    number("margin", d.margin_m, R::kNonNegative, "m", "0.04 m",
           "collision margin; a margin rounds the corners the blocks pivot on");
    number("ground_depth", d.ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    number("kinematic_highpass_hz", 0.0, R::kNonNegative, "Hz", "-",
           "kinematic drive's baseline-correction corner; 0: none (docs/bullet.md)");
    return s;
  }();
  return kSchema;
}

BulletInput MakeBulletInput(const Scene& scene, const GroundMotion& motion,
                            double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, BulletSettingsSchema());
  const DriveKind drive =
      set.Choice("drive") == "kinematic" ? DriveKind::kKinematic : DriveKind::kInertial;
  BulletInput in;
  static_cast<EngineInput&>(in) = MakeEngineInput(scene, motion, "bullet", set.Number("time_step"),
                                                  drive, set.Number("kinematic_highpass_hz"));
  in.stop_at_rest_after_s = stop_at_rest_after_s;
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
