#include "engines/ode/ode_settings.h"

#include <cmath>
#include <string>

namespace rockbench::ode {
namespace {

// The [ode] table: each key once, bound to the OdeSettings member it sets.
const SettingsTable<OdeSettings>& OdeTable() {
  using R = SettingRange;
  using S = OdeSettings;
  static const SettingsTable<S> kTable = [] {
    SettingsTable<S> t("ode");
    AddTimeStepSetting(t.unbound(), "none (the caller's)", "fixed step of dWorldStep");
    AddDriveSetting(t.unbound());
    t.Choice("stepper", &S::stepper, {OdeStepper::kWorldStep, OdeStepper::kQuickStep},
             OdeStepperName, "- (demos use quick_step)",
             "dWorldStep (Dantzig LCP, exact) or dWorldQuickStep (SOR, fixed iterations)");
    t.Integer("quick_step_iterations", &S::quick_step_iterations, 1, 100000, "20",
              "quick_step only: SOR iterations per step");
    t.Number("quick_step_w", &S::quick_step_w, R::kPositive, "", "1.3",
             "quick_step only: SOR over-relaxation, in (0, 2)", {.max = 2.0, .max_open = true});
    t.Number("erp", &S::erp, R::kUnitInterval, "", "0.2",
             "world ERP: corrects the Plane2D joints' drift (contacts use contact_erp)");
    t.Number("cfm", &S::cfm, R::kNonNegative, "m/(N s)", "1e-10", "world CFM (Plane2D rows)");
    t.Number("contact_erp", &S::contact_erp, R::kUnitInterval, "", "0.2 (the world's)",
             "fraction of a contact's penetration pushed out per step");
    t.Number("contact_cfm", &S::contact_cfm, R::kNonNegative, "m/(N s)", "1e-10 (the world's)",
             "contact softness; 0 makes dWorldStep's LCP fail");
    t.Number("contact_max_correcting_vel", &S::contact_max_correcting_vel_mps,
             R::kNonNegativeOrInfinite, "m/s", "inf",
             "cap of the push-out velocity; ODE has no split impulse, so uncapped it bounces "
             "every landing");
    t.Number("contact_surface_layer", &S::contact_surface_layer_m, R::kNonNegative, "m", "0",
             "penetration allowed without correction");
    t.Number("friction", &S::friction, R::kNonNegativeOrInfinite, "", "none (the caller's)",
             "Coulomb coefficient; inf: never slips (the model's assumption)");
    t.Flag("friction_pyramid", &S::friction_pyramid, "false",
           "dContactApprox1: bound friction by mu times the normal force (needs a finite mu)");
    t.Number("restitution", &S::restitution, R::kUnitInterval, "", "0 (no dContactBounce)",
             "the impact loses energy by the geometry, as in the model");
    t.Integer("max_contacts", &S::max_contacts, 1, 8, "- (dCollide's)",
              "contact points per box pair; 8 (no culling) keeps a face's four corners");
    t.Flag("finite_rotation", &S::finite_rotation, "false",
           "exact rotation of a step instead of the tangent update");
    t.Flag("cylinder_upright_rim", &S::cylinder_upright_rim, "false (its collider as it is)",
           "cylinder only: within 4.5e-4 rad of upright, contact at the lowest rim point (ODE's "
           "collider makes none until the face's centre is under the plane)");
    t.Number("ground_depth", &S::ground_depth_m, R::kPositive, "m", "-", "ground box thickness");
    AddKinematicHighpassSetting(t.unbound());
    return t;
  }();
  return kTable;
}

}  // namespace

const EngineSettingsSchema& OdeSettingsSchema() {
  return OdeTable().schema();
}

OdeRun MakeOdeRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s) {
  OdeRun run = MakeEngineRunInput(scene, motion, OdeTable(), stop_at_rest_after_s);
  // Two keys together, which the schema (one key at a time) cannot say: the pyramid needs a
  // finite friction.
  if (run.settings.friction_pyramid && !std::isfinite(run.settings.friction)) {
    throw SceneError(scene.path.string() +
                     ": ode.friction_pyramid = true needs a finite ode.friction (ODE multiplies "
                     "it by the normal force)");
  }
  return run;
}

}  // namespace rockbench::ode
