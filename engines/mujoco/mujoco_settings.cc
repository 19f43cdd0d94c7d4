#include "engines/mujoco/mujoco_settings.h"

#include <string>
#include <utility>

namespace rockbench::mujoco {

const EngineSettingsSchema& MujocoSettingsSchema() {
  using R = SettingRange;
  static const EngineSettingsSchema kSchema = [] {
    EngineSettingsSchema s;
    s.engine = "mujoco";
    const MujocoSettings d;
    AddTimeStepSetting(
        s, "0.002 s",
        "fixed step; with the stiff contact it also sets the contact's time constant (2 dt)");
    s.Choice("drive", "inertial", {"inertial"}, "-",
             "base motion as tilted gravity; the kinematic drive is refused (mocap bodies have no "
             "velocity in the contact equations)");
    s.Choice("contact", std::string(ContactModelName(d.contact)), {"stiff", "mujoco_default"},
             "mujoco_default (solref 0.02 s, solimp 0.9..0.95)",
             "stiff: solref 2 dt, damping ratio 10, solimp 0.9999, the only one that converges "
             "as dt falls; mujoco_default: MuJoCo's soft contact, 2e-3 rad off whatever the step");
    s.Number("stiff_timeconst_steps", d.stiff_timeconst_steps, R::kPositive, "",
             "- (0.02 s whatever dt)",
             "stiff: solref time constant in steps; 2 is MuJoCo's stiffest (it raises smaller "
             "time constants to 2 dt)",
             {.min = 2.0});
    s.Number("stiff_dampratio", d.stiff_dampratio, R::kPositive, "", "1",
             "stiff: solref damping ratio; at 1 a landing rebounds up to 25%");
    s.Choice("solver", std::string(SolverName(d.solver)), {"newton", "cg", "pgs"}, "newton",
             "constraint solver");
    s.Integer("iterations", d.iterations, 1, 100000, "100", "solver iterations at most");
    s.Number("tolerance", d.tolerance, R::kNonNegative, "", "1e-8", "solver tolerance");
    s.Choice("integrator", std::string(IntegratorName(d.integrator)), {"euler", "rk4", "implicit"},
             "euler", "integrator (semi-implicit Euler; the contacts' error is O(dt) either way)");
    s.Choice("cone", std::string(ConeName(d.cone)), {"pyramidal", "elliptic"}, "pyramidal",
             "friction cone; a pyramidal cone with large friction softens the normal contact");
    s.Number("impratio", d.impratio, R::kPositive, "", "1", "friction to normal impedance ratio");
    s.Number("friction", d.friction, R::kNonNegative, "", "1",
             "Coulomb coefficient of every geom (at least MuJoCo's mjMINMU, 1e-5); the stack "
             "needs 1.28 at the interface",
             {.min = 1e-5});
    s.Integer("noslip_iterations", d.noslip_iterations, 0, 100000, "0", "noslip post-iterations");
    s.Number("noslip_tolerance", d.noslip_tolerance, R::kNonNegative, "", "1e-6",
             "noslip tolerance");
    return s;
  }();
  return kSchema;
}

MujocoRun MakeMujocoRun(const Scene& scene, const GroundMotion& motion,
                        double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, MujocoSettingsSchema());
  MujocoRun run;
  run.input = MakeEngineInput(scene, motion, "mujoco", set, stop_at_rest_after_s);
  MujocoSettings& s = run.settings;
  s.contact = *ParseContactModel(set.Choice("contact"));
  s.stiff_timeconst_steps = set.Number("stiff_timeconst_steps");
  s.stiff_dampratio = set.Number("stiff_dampratio");
  s.solver = *ParseSolver(set.Choice("solver"));
  s.iterations = static_cast<int>(set.Integer("iterations"));
  s.tolerance = set.Number("tolerance");
  s.integrator = *ParseIntegrator(set.Choice("integrator"));
  s.cone = *ParseCone(set.Choice("cone"));
  s.impratio = set.Number("impratio");
  s.friction = set.Number("friction");
  s.noslip_iterations = static_cast<int>(set.Integer("noslip_iterations"));
  s.noslip_tolerance = set.Number("noslip_tolerance");
  return run;
}

}  // namespace rockbench::mujoco
