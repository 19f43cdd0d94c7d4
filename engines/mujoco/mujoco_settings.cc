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
    const auto number = [&](const char* key, double v, R range, const char* unit,
                            const char* mujoco_default, const char* doc) {
      SettingDef def;
      def.key = key, def.default_value = v, def.range = range, def.unit = unit;
      def.engine_default = mujoco_default, def.doc = doc;
      s.settings.push_back(def);
    };
    const auto choice = [&](const char* key, std::string_view v, std::vector<std::string> choices,
                            const char* mujoco_default, const char* doc) {
      SettingDef def;
      def.key = key, def.default_value = std::string(v), def.choices = std::move(choices);
      def.engine_default = mujoco_default, def.doc = doc;
      s.settings.push_back(def);
    };
    const auto integer = [&](std::string key, int v, std::int64_t lo, std::int64_t hi,
                             std::string mujoco_default, std::string doc) {
      SettingDef def;
      def.key = std::move(key), def.default_value = std::int64_t{v}, def.min_integer = lo;
      def.max_integer = hi, def.engine_default = std::move(mujoco_default);
      def.doc = std::move(doc);
      s.settings.push_back(std::move(def));
    };
    number("time_step", d.time_step_s, R::kPositive, "s", "0.002 s",
           "fixed step; with the stiff contact it also sets the contact's time constant (2 dt)");
    choice("drive", "inertial", {"inertial"}, "-",
           "base motion as tilted gravity; the kinematic drive is refused (mocap bodies have no "
           "velocity in the contact equations)");
    choice("contact", ContactModelName(d.contact), {"stiff", "mujoco_default"},
           "mujoco_default (solref 0.02 s, solimp 0.9..0.95)",
           "stiff: solref 2 dt, damping ratio 10, solimp 0.9999, the only one that converges "
           "as dt falls; mujoco_default: MuJoCo's soft contact, 2e-3 rad off whatever the step");
    number("stiff_timeconst_steps", d.stiff_timeconst_steps, R::kPositive, "",
           "- (0.02 s whatever dt)",
           "stiff: solref time constant in steps; 2 is MuJoCo's stiffest");
    number("stiff_dampratio", d.stiff_dampratio, R::kPositive, "", "1",
           "stiff: solref damping ratio; at 1 a landing rebounds up to 25%");
    choice("solver", SolverName(d.solver), {"newton", "cg", "pgs"}, "newton", "constraint solver");
    integer("iterations", d.iterations, 1, 100000, "100", "solver iterations at most");
    number("tolerance", d.tolerance, R::kNonNegative, "", "1e-8", "solver tolerance");
    choice("integrator", IntegratorName(d.integrator), {"euler", "rk4", "implicit"}, "euler",
           "integrator (semi-implicit Euler; the contacts' error is O(dt) either way)");
    choice("cone", ConeName(d.cone), {"pyramidal", "elliptic"}, "pyramidal",
           "friction cone; a pyramidal cone with large friction softens the normal contact");
    number("impratio", d.impratio, R::kPositive, "", "1", "friction to normal impedance ratio");
    number("friction", d.friction, R::kNonNegative, "", "1",
           "Coulomb coefficient of every geom; the stack needs 1.28 at the interface");
    integer("noslip_iterations", d.noslip_iterations, 0, 100000, "0", "noslip post-iterations");
    number("noslip_tolerance", d.noslip_tolerance, R::kNonNegative, "", "1e-6", "noslip tolerance");
    return s;
  }();
  return kSchema;
}

MujocoRun MakeMujocoRun(const Scene& scene, const GroundMotion& motion,
                        double stop_at_rest_after_s) {
  const EngineSettings set = ResolveEngineSettings(scene, MujocoSettingsSchema());
  MujocoRun run;
  run.input =
      MakeEngineInput(scene, motion, "mujoco", set.Number("time_step"), DriveKind::kInertial, 0.0);
  run.input.stop_at_rest_after_s = stop_at_rest_after_s;
  MujocoSettings& s = run.settings;
  s.time_step_s = set.Number("time_step");
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
