#include "engines/ode/ode_settings.h"

#include <cmath>
#include <string>

namespace rockbench::ode {

const EngineSettingsSchema& OdeSettingsSchema() {
  using R = SettingRange;
  static const EngineSettingsSchema kSchema = [] {
    EngineSettingsSchema s;
    s.engine = "ode";
    const OdeSettings d;
    const auto number = [&](const char* key, double v, R range, const char* unit,
                            const char* ode_default, const char* doc) {
      SettingDef def;
      def.key = key, def.default_value = v, def.range = range, def.unit = unit;
      def.engine_default = ode_default, def.doc = doc;
      s.settings.push_back(def);
    };
    const auto flag = [&](const char* key, bool v, const char* ode_default, const char* doc) {
      SettingDef def;
      def.key = key, def.default_value = v, def.engine_default = ode_default, def.doc = doc;
      s.settings.push_back(def);
    };
    number("time_step", d.time_step_s, R::kPositive, "s", "none (the caller's)",
           "fixed step of dWorldStep");
    SettingDef drive;
    drive.key = "drive", drive.default_value = std::string("inertial");
    drive.choices = {"inertial", "kinematic"}, drive.engine_default = "-";
    drive.doc = "base motion as tilted gravity (inertial) or a moving ground (kinematic)";
    s.settings.push_back(drive);
    SettingDef stepper;
    stepper.key = "stepper", stepper.default_value = std::string(OdeStepperName(d.stepper));
    stepper.choices = {"world_step", "quick_step"};
    stepper.engine_default = "- (demos use quick_step)";
    stepper.doc = "dWorldStep (Dantzig LCP, exact) or dWorldQuickStep (SOR, fixed iterations)";
    s.settings.push_back(stepper);
    SettingDef it;
    it.key = "quick_step_iterations", it.default_value = std::int64_t{d.quick_step_iterations};
    it.min_integer = 1, it.max_integer = 100000, it.engine_default = "20";
    it.doc = "quick_step only: SOR iterations per step";
    s.settings.push_back(it);
    number("quick_step_w", d.quick_step_w, R::kPositive, "", "1.3",
           "quick_step only: SOR over-relaxation, in (0, 2)");
    number("erp", d.erp, R::kUnitInterval, "", "0.2",
           "world ERP: corrects the Plane2D joints' drift (contacts use contact_erp)");
    number("cfm", d.cfm, R::kNonNegative, "m/(N s)", "1e-10", "world CFM (Plane2D rows)");
    number("contact_erp", d.contact_erp, R::kUnitInterval, "", "0.2 (the world's)",
           "fraction of a contact's penetration pushed out per step");
    number("contact_cfm", d.contact_cfm, R::kNonNegative, "m/(N s)", "1e-10 (the world's)",
           "contact softness; 0 makes dWorldStep's LCP fail");
    number("contact_max_correcting_vel", d.contact_max_correcting_vel_mps,
           R::kNonNegativeOrInfinite, "m/s", "inf",
           "cap of the push-out velocity; ODE has no split impulse, so uncapped it bounces "
           "every landing");
    number("contact_surface_layer", d.contact_surface_layer_m, R::kNonNegative, "m", "0",
           "penetration allowed without correction");
    number("friction", d.friction, R::kNonNegativeOrInfinite, "", "none (the caller's)",
           "Coulomb coefficient; inf: never slips (the model's assumption)");
    flag("friction_pyramid", d.friction_pyramid, "false",
         "dContactApprox1: bound friction by mu times the normal force (needs a finite mu)");
    number("restitution", d.restitution, R::kUnitInterval, "", "0 (no dContactBounce)",
           "the impact loses energy by the geometry, as in the model");
    SettingDef contacts;
    contacts.key = "max_contacts", contacts.default_value = std::int64_t{d.max_contacts};
    contacts.min_integer = 1, contacts.max_integer = 8, contacts.engine_default = "- (dCollide's)";
    contacts.doc = "contact points per box pair; 8 (no culling) keeps a face's four corners";
    s.settings.push_back(contacts);
    flag("finite_rotation", d.finite_rotation, "false",
         "exact rotation of a step instead of the tangent update");
    number("ground_depth", d.ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    number("kinematic_highpass_hz", 0.0, R::kNonNegative, "Hz", "-",
           "kinematic drive's baseline-correction corner; 0: none (docs/bullet.md)");
    return s;
  }();
  return kSchema;
}

OdeRun MakeOdeRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, OdeSettingsSchema());
  const DriveKind drive =
      set.Choice("drive") == "kinematic" ? DriveKind::kKinematic : DriveKind::kInertial;
  OdeRun run;
  run.input = MakeEngineInput(scene, motion, "ode", set.Number("time_step"), drive,
                              set.Number("kinematic_highpass_hz"));
  run.input.stop_at_rest_after_s = stop_at_rest_after_s;
  OdeSettings& s = run.settings;
  s.time_step_s = set.Number("time_step");
  s.stepper = *ParseOdeStepper(set.Choice("stepper"));
  s.quick_step_iterations = static_cast<int>(set.Integer("quick_step_iterations"));
  s.quick_step_w = set.Number("quick_step_w");
  if (!(s.quick_step_w < 2.0)) {
    throw SceneError(scene.path.string() + ": ode.quick_step_w: expected a number in (0, 2), got " +
                     SettingText(s.quick_step_w));
  }
  s.erp = set.Number("erp");
  s.cfm = set.Number("cfm");
  s.contact_erp = set.Number("contact_erp");
  s.contact_cfm = set.Number("contact_cfm");
  s.contact_max_correcting_vel_mps = set.Number("contact_max_correcting_vel");
  s.contact_surface_layer_m = set.Number("contact_surface_layer");
  s.friction = set.Number("friction");
  s.friction_pyramid = set.Flag("friction_pyramid");
  if (s.friction_pyramid && !std::isfinite(s.friction)) {
    throw SceneError(scene.path.string() +
                     ": ode.friction_pyramid = true needs a finite ode.friction (ODE multiplies "
                     "it by the normal force)");
  }
  s.restitution = set.Number("restitution");
  s.max_contacts = static_cast<int>(set.Integer("max_contacts"));
  s.finite_rotation = set.Flag("finite_rotation");
  s.ground_depth_m = set.Number("ground_depth");
  return run;
}

}  // namespace rockbench::ode
