#pragma once
/// Settings of the MuJoCo engine (2.2.2): ours, with MuJoCo's own default beside each and why
/// ours differs. Free of MuJoCo headers. Each maps onto an MJCF <option> or <geom> attribute
/// (MujocoWorld::Settings() lists the values in use). The measurements behind ours are in
/// docs/engine-measurements.md, MuJoCo.
#include <array>
#include <string_view>

#include "engines/common/engine_input.h"
#include "scene/engine_settings.h"

namespace rockbench::mujoco {

/// How the contacts are regularised (MuJoCo's soft constraints: the geoms' solref and solimp).
///
/// MuJoCo drives a contact's penetration r and normal velocity v towards the reference
/// acceleration aref = -b v - k r, with b = 2 / (dmax timeconst) and
/// k = 1 / (dmax^2 timeconst^2 dampratio^2), and lets a fraction 1 - d (the impedance d from
/// solimp) of the constraint force go unenforced.
enum class ContactModel {
  /// solref = (stiff_timeconst_steps * dt, stiff_dampratio), solimp = stiff_solimp. With the
  /// time constant at 2 dt, b dt = 1: a landing corner's approach velocity is removed in one
  /// step, the plastic impact of the rigid model (no restitution; Housner's energy loss comes
  /// from the geometry alone). Converges to the rigid model as dt falls (measured:
  /// docs/engine-measurements.md, MuJoCo).
  kStiff,
  /// MuJoCo's own: solref (0.02 s, 1), solimp (0.9, 0.95, 0.001 m, 0.5, 2), whatever the step.
  /// A 20 ms spring under each corner: 2.7 mm (block) to 6 mm (stack) of penetration, an
  /// impact spread over ~20 ms, errors that do not shrink with dt (measured:
  /// docs/engine-measurements.md, MuJoCo). Kept to show what MuJoCo's defaults do.
  kMujocoDefault,
};

/// MuJoCo's constraint solver (mjtSolver).
enum class Solver { kNewton, kCG, kPGS };
/// MuJoCo's integrator (mjtIntegrator): semi-implicit Euler, RK4, implicit in velocity.
enum class Integrator { kEuler, kRK4, kImplicit };
/// MuJoCo's friction cone (mjtCone).
enum class Cone { kPyramidal, kElliptic };

/// The [mujoco] settings besides the time step, which is EngineInput::time_step_s (MuJoCo's
/// default 0.002 s; ours 1e-4 s, as Bullet's: with the stiff contact the step sets both the
/// integration error and the contact's compliance, time constant 2 dt).
struct MujocoSettings {
  /// Contact regularisation. MuJoCo default: kMujocoDefault's values. Ours kStiff, the only one
  /// that converges to the rigid-block model as dt falls.
  ContactModel contact = ContactModel::kStiff;
  /// kStiff: solref time constant in steps (timeconst = this * dt), dimensionless. MuJoCo's
  /// default time constant is 0.02 s whatever dt; its "refsafe" rule raises any time constant
  /// below 2 dt to 2 dt, so 2 is the stiffest contact MuJoCo integrates, and the one whose
  /// damping removes an approach velocity in exactly one step (at 5 or 10 steps the impact
  /// spreads over that many steps and the errors grow: measured).
  double stiff_timeconst_steps = 2.0;
  /// kStiff: solref damping ratio, dimensionless. MuJoCo default 1 (critical). Ours 10: with
  /// the time constant at 2 dt the stiffness term k r turns the penetration a landing corner
  /// makes within its step (up to v dt) into a rebound velocity of up to v / (4 dampratio^2),
  /// whatever dt: at 1 that is a restitution of up to 25% at the landing corner, which the
  /// rigid model does not have. At 10 the rebound is below 0.25% and the penetration is
  /// recovered over 4 dampratio^2 = 400 steps (the penetration itself is O(v dt)). Measured:
  /// docs/engine-measurements.md, MuJoCo.
  double stiff_dampratio = 10.0;
  /// kStiff: solimp (dmin, dmax, width m, midpoint, power). MuJoCo default
  /// (0.9, 0.95, 0.001 m, 0.5, 2): 5-10% of the constraint force left unenforced, which shows
  /// as creep and softer impacts. Ours: the impedance at MuJoCo's largest, mjMAXIMP = 0.9999, at
  /// every penetration (width, midpoint and power then play no part): the rigid model's contact
  /// (measured: docs/engine-measurements.md, MuJoCo).
  std::array<double, 5> stiff_solimp = {0.9999, 0.9999, 0.001, 0.5, 2.0};

  /// Constraint solver. MuJoCo default Newton (kept: CG and PGS are slower and no more
  /// accurate here; measured: docs/engine-measurements.md, MuJoCo).
  Solver solver = Solver::kNewton;
  /// Maximum solver iterations. MuJoCo default 100 (kept: Newton stops at the tolerance long
  /// before).
  int iterations = 100;
  /// Solver tolerance (relative cost improvement), dimensionless. MuJoCo default 1e-8 (kept: a
  /// smaller one changes nothing measurable; docs/engine-measurements.md, MuJoCo).
  double tolerance = 1e-8;
  /// Integrator. MuJoCo default Euler (semi-implicit; kept: the error is the contacts' O(dt)
  /// either way; RK4 re-solves the contacts in each of its 4 stages and costs several times as
  /// much (docs/engine-measurements.md, MuJoCo); implicit is Euler when nothing has joint
  /// damping, as here).
  Integrator integrator = Integrator::kEuler;
  /// Friction cone. MuJoCo default pyramidal. Ours elliptic: a pyramidal cone's edges mix the
  /// normal with friction times the tangent, so their regularisation grows with the friction
  /// squared and a large friction softens the normal contact (measured:
  /// docs/engine-measurements.md, MuJoCo). The elliptic cone keeps normal and friction rows
  /// apart.
  Cone cone = Cone::kElliptic;
  /// Ratio of friction to normal impedance, dimensionless. MuJoCo default 1 (kept: the slip is
  /// already far below the monitor's flag; docs/engine-measurements.md, MuJoCo).
  double impratio = 1.0;
  /// Coulomb friction coefficient of every geom (MuJoCo takes the larger of the two geoms').
  /// MuJoCo default 1. Ours 10: the rigid model assumes no sliding, and the reference needs a
  /// friction ratio of 0.70 at the ground and 1.28 at the interface for the thesis's stack
  /// (0.24 for Housner's block), which MuJoCo's 1 would not give (docs/engine-measurements.md,
  /// MuJoCo).
  double friction = 10.0;
  /// Noslip post-iterations (remove the friction constraints' soft creep). MuJoCo default 0
  /// (kept: the slip with the stiff contact is far below the monitor's flag of 1e-3 of the
  /// width, and noslip iterations cost a second solve; docs/engine-measurements.md, MuJoCo).
  int noslip_iterations = 0;
  /// Noslip tolerance, dimensionless. MuJoCo default 1e-6 (kept).
  double noslip_tolerance = 1e-6;

  bool operator==(const MujocoSettings&) const = default;
};

/// Names as used in summaries and scene tables.
constexpr std::string_view ContactModelName(ContactModel c) {
  return c == ContactModel::kStiff ? "stiff" : "mujoco_default";
}
constexpr std::string_view SolverName(Solver s) {
  return s == Solver::kNewton ? "newton" : (s == Solver::kCG ? "cg" : "pgs");
}
constexpr std::string_view IntegratorName(Integrator i) {
  return i == Integrator::kEuler ? "euler" : (i == Integrator::kRK4 ? "rk4" : "implicit");
}
constexpr std::string_view ConeName(Cone c) {
  return c == Cone::kPyramidal ? "pyramidal" : "elliptic";
}

/// The [mujoco] table: the MujocoSettings fields a scene may set, with MuJoCo's own default
/// beside ours.
const EngineSettingsSchema& MujocoSettingsSchema();

/// The input of one MuJoCo run: the common engine input (step, drive, base motion) and the
/// settings.
using MujocoRun = EngineRunInput<MujocoSettings>;

/// Resolves the scene's [mujoco] table (SceneError naming FILE:LINE and the key for a bad value)
/// and samples the base motion on its step.
MujocoRun MakeMujocoRun(const Scene& scene, const GroundMotion& motion,
                        double stop_at_rest_after_s);

}  // namespace rockbench::mujoco
