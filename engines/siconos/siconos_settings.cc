#include "engines/siconos/siconos_settings.h"

#include <string>

namespace rockbench::siconos_engine {
namespace {

// "linear" or "nonlinear": TimeStepping's Newton loop.
const char* NewtonName(bool linear) {
  return linear ? "linear" : "nonlinear";
}

// The [siconos] table: each key once, bound to the SiconosSettings member it sets.
const SettingsTable<SiconosSettings>& SiconosTable() {
  using R = SettingRange;
  using S = SiconosSettings;
  static const SettingsTable<S> kTable = [] {
    SettingsTable<S> t("siconos");
    AddTimeStepSetting(t.unbound(), "none (TimeDiscretisation's h)",
                       "fixed step of the Moreau-Jean time stepping");
    AddDriveSetting(t.unbound());
    t.Number("theta", &S::theta, R::kUnitInterval, "", "0.5",
             "Moreau-Jean theta, in [0.5, 1] (0.5 trapezoidal, 1 implicit Euler; unstable "
             "below 0.5)",
             {.min = 0.5});
    t.Number("restitution", &S::restitution, R::kUnitInterval, "", "none",
             "Newton's normal restitution; 0 gives Housner's impact");
    t.Number("friction", &S::friction, R::kNonNegative, "", "none",
             "Coulomb coefficient of every contact; the model assumes no sliding");
    t.Choice("solver", &S::solver,
             {SiconosSolver::kLemke, SiconosSolver::kNsgs, SiconosSolver::kEnum}, SiconosSolverName,
             "- (FrictionContact's 3-D NSGS)",
             "numerics solver of the 2-D frictional contact; lemke mis-steps at rocking onset");
    t.Number("solver_tolerance", &S::solver_tolerance, R::kPositive, "",
             "1e-4 (nsgs), 1e-6 (lemke)", "numerics solver tolerance");
    t.Integer("solver_max_iterations", &S::solver_max_iterations, 1, 100000000,
              "1000 (nsgs), 10000 (lemke)", "numerics solver iteration cap");
    t.Flag("lemke_fallback", &S::lemke_fallback, "false (none)",
           "a step NSGS does not converge on is solved again by Lemke");
    t.Choice("newton", &S::newton_linear, {true, false}, NewtonName, "nonlinear",
             "TimeStepping's Newton loop; both make one iteration here");
    t.Number("activation_threshold", &S::activation_threshold_m, R::kNonNegative, "m", "0",
             "MoreauJeanOSI's constraint activation threshold (predicted gap)");
    AddKinematicHighpassSetting(t.unbound());
    return t;
  }();
  return kTable;
}

}  // namespace

const EngineSettingsSchema& SiconosSettingsSchema() {
  return SiconosTable().schema();
}

SiconosRun MakeSiconosRun(const Scene& scene, const GroundMotion& motion,
                          double stop_at_rest_after_s) {
  return MakeEngineRunInput(scene, motion, SiconosTable(), stop_at_rest_after_s);
}

}  // namespace rockbench::siconos_engine
