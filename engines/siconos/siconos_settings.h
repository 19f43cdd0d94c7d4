#pragma once
/// Settings of the Siconos engine (Siconos 4.4, Debian libsiconos-kernel-dev: the kernel and
/// numerics only, not siconos mechanics, see engines/siconos/CMakeLists.txt). Every field says
/// its unit, Siconos's own default and why ours differs.
///
/// The measurements behind ours are in docs/engine-measurements.md, Siconos.
#include <string>

#include "engines/common/engine_input.h"
#include "engines/siconos/siconos_system.h"
#include "scene/engine_settings.h"

namespace rockbench::siconos_engine {

/// The [siconos] settings besides the time step of the time discretisation, which is
/// EngineInput::time_step_s (Siconos has no default: TimeDiscretisation needs one; ours: the
/// project's 1e-4 s).
struct SiconosSettings {
  /// Moreau-Jean theta (MoreauJeanOSI(theta)): the weight of the step's end in the smooth
  /// part (theta = 0.5: trapezoidal, energy-conserving between impacts; 1: implicit Euler,
  /// dissipative; below 0.5 the scheme is unstable, so the schema refuses it). Siconos's
  /// default 0.5. Ours: the same.
  double theta = 0.5;
  /// Newton's normal restitution e of every contact (NewtonImpactFrictionNSL). Siconos has no
  /// default. Ours: 0: a landing corner stops dead and, with sticking friction, the impulse
  /// conserves the angular momentum about it (Housner's impact); the old pivot lifts off with
  /// zero impulse.
  double restitution = 0.0;
  /// Coulomb friction coefficient of every contact (NewtonImpactFrictionNSL's mu). Siconos has
  /// no default. Ours: 10, as DART's and MuJoCo's: the model assumes no sliding and the thesis
  /// stack needs |T|/N up to 1.28 at the interface.
  double friction = 10.0;
  /// Numerics solver of the 2-D frictional contact problem. Siconos's default for
  /// FrictionContact is the 3-D NSGS id (FrictionContact(dim = 3)); for dimension 2 ours is
  /// the 2-D NSGS. Lemke (the problem as an LCP) is not usable at the onset of rocking: the step
  /// where a corner unloads gets a spurious rate the wrong way (measured:
  /// docs/engine-measurements.md, Siconos).
  SiconosSolver solver = SiconosSolver::kNsgs;
  /// Solver tolerance and iteration cap (SolverOptions dparam[TOL], iparam[MAX_ITER]).
  /// Siconos's defaults: NSGS 1e-4 / 1000, Lemke 1e-6 / 10000. Ours: 1e-8 / 1000 (then Lemke): the
  /// contact impulses of a step to 1e-8 relative.
  double solver_tolerance = 1e-8;
  int solver_max_iterations = 1000;
  /// Whether a step whose NSGS did not converge within solver_max_iterations is solved again
  /// by Lemke (exact). Siconos has no fallback (TimeStepping keeps the unconverged impulses).
  /// Ours: yes: with a mass ratio of 1000 (stress catalogue) NSGS converges on no step, and
  /// Lemke after it is as accurate as ten times the iterations at a fraction of the cost
  /// (measured: docs/engine-measurements.md, Siconos).
  bool lemke_fallback = true;
  /// TimeStepping's Newton loop (setNewtonOptions). Siconos's default: SICONOS_TS_NONLINEAR,
  /// iterations until the dynamical systems' residual converges; a LagrangianLinearTIDS has
  /// none and the relations' residual is not checked by default, so it stops after one
  /// iteration, with the contact Jacobians at the step's start. Ours: SICONOS_TS_LINEAR, the same
  /// single iteration without the loop's residual bookkeeping: the same angles, faster
  /// (measured: docs/engine-measurements.md, Siconos).
  bool newton_linear = true;
  /// MoreauJeanOSI's constraint activation threshold, m: a contact whose gap predicted at the
  /// step's end is below it enters the step's contact problem. Siconos's default: 0. Ours: the
  /// same (EXPERIMENT).
  double activation_threshold_m = 0.0;

  bool operator==(const SiconosSettings&) const = default;
};

/// The [siconos] table: every SiconosSettings field, with Siconos's own default beside ours.
const EngineSettingsSchema& SiconosSettingsSchema();

/// The input of one Siconos run: the common engine input and the settings.
using SiconosRun = EngineRunInput<SiconosSettings>;

/// Resolves the scene's [siconos] table (SceneError naming FILE:LINE and the key for a bad
/// value) and samples the base motion on its step.
SiconosRun MakeSiconosRun(const Scene& scene, const GroundMotion& motion,
                          double stop_at_rest_after_s);

}  // namespace rockbench::siconos_engine
