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
    AddTimeStepSetting(s, "none (the caller's)", "fixed step of dWorldStep");
    AddDriveSetting(s);
    s.Choice("stepper", OdeStepperName(d.stepper), {"world_step", "quick_step"},
             "- (demos use quick_step)",
             "dWorldStep (Dantzig LCP, exact) or dWorldQuickStep (SOR, fixed iterations)");
    s.Integer("quick_step_iterations", d.quick_step_iterations, 1, 100000, "20",
              "quick_step only: SOR iterations per step");
    s.Number("quick_step_w", d.quick_step_w, R::kPositive, "", "1.3",
             "quick_step only: SOR over-relaxation, in (0, 2)", {.max = 2.0, .max_open = true});
    s.Number("erp", d.erp, R::kUnitInterval, "", "0.2",
             "world ERP: corrects the Plane2D joints' drift (contacts use contact_erp)");
    s.Number("cfm", d.cfm, R::kNonNegative, "m/(N s)", "1e-10", "world CFM (Plane2D rows)");
    s.Number("contact_erp", d.contact_erp, R::kUnitInterval, "", "0.2 (the world's)",
             "fraction of a contact's penetration pushed out per step");
    s.Number("contact_cfm", d.contact_cfm, R::kNonNegative, "m/(N s)", "1e-10 (the world's)",
             "contact softness; 0 makes dWorldStep's LCP fail");
    s.Number("contact_max_correcting_vel", d.contact_max_correcting_vel_mps,
             R::kNonNegativeOrInfinite, "m/s", "inf",
             "cap of the push-out velocity; ODE has no split impulse, so uncapped it bounces "
             "every landing");
    s.Number("contact_surface_layer", d.contact_surface_layer_m, R::kNonNegative, "m", "0",
             "penetration allowed without correction");
    s.Number("friction", d.friction, R::kNonNegativeOrInfinite, "", "none (the caller's)",
             "Coulomb coefficient; inf: never slips (the model's assumption)");
    s.Flag("friction_pyramid", d.friction_pyramid, "false",
           "dContactApprox1: bound friction by mu times the normal force (needs a finite mu)");
    s.Number("restitution", d.restitution, R::kUnitInterval, "", "0 (no dContactBounce)",
             "the impact loses energy by the geometry, as in the model");
    s.Integer("max_contacts", d.max_contacts, 1, 8, "- (dCollide's)",
              "contact points per box pair; 8 (no culling) keeps a face's four corners");
    s.Flag("finite_rotation", d.finite_rotation, "false",
           "exact rotation of a step instead of the tangent update");
    s.Number("ground_depth", d.ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(s);
    return s;
  }();
  return kSchema;
}

OdeRun MakeOdeRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, OdeSettingsSchema());
  OdeRun run;
  run.input = MakeEngineInput(scene, motion, "ode", set, stop_at_rest_after_s);
  OdeSettings& s = run.settings;
  s.stepper = *ParseOdeStepper(set.Choice("stepper"));
  s.quick_step_iterations = static_cast<int>(set.Integer("quick_step_iterations"));
  s.quick_step_w = set.Number("quick_step_w");
  s.erp = set.Number("erp");
  s.cfm = set.Number("cfm");
  s.contact_erp = set.Number("contact_erp");
  s.contact_cfm = set.Number("contact_cfm");
  s.contact_max_correcting_vel_mps = set.Number("contact_max_correcting_vel");
  s.contact_surface_layer_m = set.Number("contact_surface_layer");
  s.friction = set.Number("friction");
  s.friction_pyramid = set.Flag("friction_pyramid");
  // Two keys together, which the schema (one key at a time) cannot say: the pyramid needs a
  // finite friction.
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
