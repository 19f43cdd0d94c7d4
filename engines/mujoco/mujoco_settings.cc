#include "engines/mujoco/mujoco_settings.h"

#include <string>

namespace rockbench::mujoco {
namespace {

// The [mujoco] table: each key once, bound to the MujocoSettings member it sets.
const SettingsTable<MujocoSettings>& MujocoTable() {
  using R = SettingRange;
  using S = MujocoSettings;
  static const SettingsTable<S> kTable = [] {
    SettingsTable<S> t("mujoco");
    AddTimeStepSetting(
        t.unbound(), "0.002 s",
        "fixed step; with the stiff contact it also sets the contact's time constant (2 dt)");
    AddDriveSetting(t.unbound(), {"inertial"},
                    "base motion as tilted gravity; the kinematic drive is refused (mocap bodies "
                    "have no velocity in the contact equations)");
    t.Choice("contact", &S::contact, {ContactModel::kStiff, ContactModel::kMujocoDefault},
             ContactModelName, "mujoco_default (solref 0.02 s, solimp 0.9..0.95)",
             "stiff: solref 2 dt, damping ratio 10, solimp 0.9999, the only one that converges "
             "as dt falls; mujoco_default: MuJoCo's soft contact, 2e-3 rad off whatever the step");
    t.Number("stiff_timeconst_steps", &S::stiff_timeconst_steps, R::kPositive, "",
             "- (0.02 s whatever dt)",
             "stiff: solref time constant in steps; 2 is MuJoCo's stiffest (it raises smaller "
             "time constants to 2 dt)",
             {.min = 2.0});
    t.Number("stiff_dampratio", &S::stiff_dampratio, R::kPositive, "", "1",
             "stiff: solref damping ratio; at 1 a landing rebounds up to 25%");
    t.Choice("solver", &S::solver, {Solver::kNewton, Solver::kCG, Solver::kPGS}, SolverName,
             "newton", "constraint solver");
    t.Integer("iterations", &S::iterations, 1, 100000, "100", "solver iterations at most");
    t.Number("tolerance", &S::tolerance, R::kNonNegative, "", "1e-8", "solver tolerance");
    t.Choice("integrator", &S::integrator,
             {Integrator::kEuler, Integrator::kRK4, Integrator::kImplicit}, IntegratorName, "euler",
             "integrator (semi-implicit Euler; the contacts' error is O(dt) either way)");
    t.Choice("cone", &S::cone, {Cone::kPyramidal, Cone::kElliptic}, ConeName, "pyramidal",
             "friction cone; a pyramidal cone with large friction softens the normal contact");
    t.Number("impratio", &S::impratio, R::kPositive, "", "1", "friction to normal impedance ratio");
    t.Number("friction", &S::friction, R::kNonNegative, "", "1",
             "Coulomb coefficient of every geom (at least MuJoCo's mjMINMU, 1e-5); the stack "
             "needs 1.28 at the interface",
             {.min = 1e-5});
    t.Integer("noslip_iterations", &S::noslip_iterations, 0, 100000, "0", "noslip post-iterations");
    t.Number("noslip_tolerance", &S::noslip_tolerance, R::kNonNegative, "", "1e-6",
             "noslip tolerance");
    return t;
  }();
  return kTable;
}

}  // namespace

const EngineSettingsSchema& MujocoSettingsSchema() {
  return MujocoTable().schema();
}

MujocoRun MakeMujocoRun(const Scene& scene, const GroundMotion& motion,
                        double stop_at_rest_after_s) {
  return MakeEngineRunInput(scene, motion, MujocoTable(), stop_at_rest_after_s);
}

}  // namespace rockbench::mujoco
