#include "engines/siconos/siconos_settings.h"

#include <string>

namespace rockbench::siconos_engine {

const EngineSettingsSchema& SiconosSettingsSchema() {
  using R = SettingRange;
  static const EngineSettingsSchema kSchema = [] {
    EngineSettingsSchema s;
    s.engine = "siconos";
    const SiconosSettings d;
    AddTimeStepSetting(s, "none (TimeDiscretisation's h)",
                       "fixed step of the Moreau-Jean time stepping");
    AddDriveSetting(s);
    s.Number("theta", d.theta, R::kUnitInterval, "", "0.5",
             "Moreau-Jean theta, in [0.5, 1] (0.5 trapezoidal, 1 implicit Euler; unstable "
             "below 0.5)",
             {.min = 0.5});
    s.Number("restitution", d.restitution, R::kUnitInterval, "", "none",
             "Newton's normal restitution; 0 gives Housner's impact");
    s.Number("friction", d.friction, R::kNonNegative, "", "none",
             "Coulomb coefficient of every contact; the model assumes no sliding");
    s.Choice("solver", SiconosSolverName(d.solver), {"lemke", "nsgs", "enum"},
             "- (FrictionContact's 3-D NSGS)",
             "numerics solver of the 2-D frictional contact; lemke mis-steps at rocking onset");
    s.Number("solver_tolerance", d.solver_tolerance, R::kPositive, "", "1e-4 (nsgs), 1e-6 (lemke)",
             "numerics solver tolerance");
    s.Integer("solver_max_iterations", d.solver_max_iterations, 1, 100000000,
              "1000 (nsgs), 10000 (lemke)", "numerics solver iteration cap");
    s.Flag("lemke_fallback", d.lemke_fallback, "false (none)",
           "a step NSGS does not converge on is solved again by Lemke");
    s.Choice("newton", d.newton_linear ? "linear" : "nonlinear", {"linear", "nonlinear"},
             "nonlinear", "TimeStepping's Newton loop; both make one iteration here");
    s.Number("activation_threshold", d.activation_threshold_m, R::kNonNegative, "m", "0",
             "MoreauJeanOSI's constraint activation threshold (predicted gap)");
    AddKinematicHighpassSetting(s);
    return s;
  }();
  return kSchema;
}

SiconosRun MakeSiconosRun(const Scene& scene, const GroundMotion& motion,
                          double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, SiconosSettingsSchema());
  SiconosRun run;
  run.input = MakeEngineInput(scene, motion, "siconos", set, stop_at_rest_after_s);
  SiconosSettings& s = run.settings;
  s.theta = set.Number("theta");
  s.restitution = set.Number("restitution");
  s.friction = set.Number("friction");
  const std::string solver = set.Choice("solver");
  s.solver = solver == "nsgs"   ? SiconosSolver::kNsgs
             : solver == "enum" ? SiconosSolver::kEnum
                                : SiconosSolver::kLemke;
  s.solver_tolerance = set.Number("solver_tolerance");
  s.solver_max_iterations = static_cast<int>(set.Integer("solver_max_iterations"));
  s.lemke_fallback = set.Flag("lemke_fallback");
  s.newton_linear = set.Choice("newton") == "linear";
  s.activation_threshold_m = set.Number("activation_threshold");
  return run;
}

}  // namespace rockbench::siconos_engine
