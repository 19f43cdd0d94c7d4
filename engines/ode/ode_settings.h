#pragma once
/// Settings of the ODE engine (Open Dynamics Engine 0.16, double precision). Defaults are ours,
/// chosen for rocking blocks; ODE's own defaults are given with each field. ODE 0.16.2's world
/// defaults were read back from a fresh dWorldCreate() (erp 0.2, cfm 1e-10, surface layer 0,
/// max correcting velocity infinity, QuickStep 20 iterations with w = 1.3) and bodies'
/// (finite rotation off, gyroscopic on).
#include <limits>

#include "engines/common/engine_input.h"
#include "scene/engine_settings.h"

namespace rockbench::ode {

/// The ODE stepper.
enum class OdeStepper {
  /// dWorldStep: builds the island's full constraint matrix and solves the mixed LCP with
  /// Dantzig's pivoting method (exact to round-off). O(m^3) in the number of constraint rows,
  /// which here is at most about 40: the accurate choice.
  kWorldStep,
  /// dWorldQuickStep: projected Gauss-Seidel (SOR) with a fixed number of iterations; does not
  /// converge fully at impacts (the stack's rows are strongly coupled).
  kQuickStep,
};

/// "world_step" or "quick_step".
const char* OdeStepperName(OdeStepper stepper);

/// The [ode] settings besides the time step, which is EngineInput::time_step_s (ODE has no
/// default: the caller passes it to every dWorldStep).
struct OdeSettings {
  /// Stepper (ODE offers both; its demos mostly use QuickStep for speed). Ours: dWorldStep, the
  /// exact LCP solve: two boxes give at most ~40 rows, so it is also the faster one here.
  /// QuickStep is less accurate at impacts and slower at equal accuracy (measurements:
  /// docs/engine-measurements.md, ODE).
  OdeStepper stepper = OdeStepper::kWorldStep;
  /// QuickStep only: SOR iterations per step (ODE default 20). Ours: 100; unused by dWorldStep.
  int quick_step_iterations = 100;
  /// QuickStep only: SOR over-relaxation w, in (0, 2) (ODE default 1.3). Unused by dWorldStep.
  double quick_step_w = 1.3;

  /// World ERP, dimensionless (ODE default 0.2): the fraction of a joint error removed in one
  /// step. Here it only corrects the Plane2D joints' drift out of z = 0 (contacts use
  /// contact_erp). ODE's default.
  double erp = 0.2;
  /// World CFM, m/(N s) for a row whose force is in N (ODE default 1e-10 in double precision):
  /// constraint force mixing, the regularisation of every row, also what makes the redundant
  /// rows of a box lying on a face (four corner points, the Plane2D rows) solvable. Here it
  /// applies to the Plane2D rows (contacts use contact_cfm). ODE's default.
  double cfm = 1e-10;

  /// Contact ERP, dimensionless (ODE: the world ERP, 0.2, unless dContactSoftERP): a contact
  /// penetrating by d (minus contact_surface_layer_m) is pushed out at contact_erp d / dt,
  /// capped at contact_max_correcting_vel_mps. ODE's default value. ODE has no split impulse:
  /// the push-out velocity stays in the body, so uncapped it acts after every impact as a
  /// restitution of up to contact_erp on the landing corner's velocity (the landing step sinks
  /// the corner by up to v dt). The cap, not this fraction, is what keeps that bounce small.
  double contact_erp = 0.2;
  /// Contact CFM, m/(N s) (ODE: the world CFM unless dContactSoftCFM). Ours: ODE's default
  /// 1e-10. With contact_erp the pair is ODE's spring-damper k = erp / (dt cfm), c = (1 - erp)
  /// / cfm: 2e13 N/m and 8e9 N s/m at dt = 1e-4 s, rigid for our blocks. A contact carrying a
  /// force F creeps in at cfm F unless the push-out holds it: 2.5e-6 m/s under each corner of
  /// the thesis stack (2.5e4 N), which contact_erp = 0 leaves uncorrected (measured: block 1
  /// sank 7.5 um in 3 s at rest). Smaller values (1e-14) reduce the creep but leave the
  /// redundant rows of a face contact nearly singular; 0 makes dWorldStep's LCP fail (ODE prints
  /// "LCP internal error" at almost every step).
  double contact_cfm = 1e-10;
  /// Cap of the contact push-out velocity, m/s (ODE default infinity,
  /// dWorldSetContactMaxCorrectingVel). Ours: 1e-4 m/s, from the physics of the blocks rather
  /// than a fit: far below the landing corners' speeds (0.05..1 m/s), so the artificial bounce
  /// is <= 1e-4 m/s;
  /// far above the creep cfm F (2.5e-6 m/s for the thesis stack; contacts up to 1e6 N per
  /// point stay held); and fast enough to remove a landing's overshoot (v dt ~ 2e-5 m at
  /// dt = 1e-4 s) in ~0.2 s, before the next impact, so that the pivot is back at the
  /// surface (measurements against other caps and ODE's defaults: docs/engine-measurements.md,
  /// ODE).
  double contact_max_correcting_vel_mps = 1e-4;
  /// Penetration allowed without correction, m (ODE default 0, dWorldSetContactSurfaceLayer).
  /// ODE's default: a layer makes resting contacts sit that deep, and does not stop the bounce
  /// of landings that sink deeper.
  double contact_surface_layer_m = 0.0;

  /// Coulomb friction coefficient (ODE has no default; dInfinity means "never slips"). Ours:
  /// infinity, rows without bounds: the model assumes the blocks never slide. The first
  /// friction direction is set to the contact's in-plane tangent (dContactFDir1), the second
  /// (along z) is redundant with the Plane2D joint. With friction_pyramid a finite value is
  /// needed (ODE multiplies it by the normal force: infinity times zero would be NaN).
  double friction = std::numeric_limits<double>::infinity();
  /// dContactApprox1 (ODE default off: friction bounded by a constant force mu, in N): the
  /// friction pyramid |f_t| <= mu f_n, each tangent direction separately. Ours: off, with
  /// friction = infinity (no bound at all); turn on with a finite friction for Coulomb. With it
  /// the thesis stack slides at impacts even at friction 10 (measurements:
  /// docs/engine-measurements.md, ODE).
  bool friction_pyramid = false;
  /// Restitution of the contacts (dContactBounce; ODE default off). Ours: 0 and off: Housner's
  /// impact is perfectly plastic at the landing corner; the energy it loses follows from the
  /// geometry (rate ratio 1 - 1.5 sin^2 alpha), not from a coefficient.
  double restitution = 0.0;
  /// Contact points per box pair passed to dCollide (ODE's box-box collider makes up to 8 by
  /// face clipping and culls to this many). A box on a face needs 4 (its face's corners), a
  /// rocking one 2 (both ends of its pivot edge); block 2 on block 1 made up to 6 at some
  /// steps. Ours: 8, the collider's maximum: no culling (2 culls a face contact to one z side;
  /// measurements: docs/engine-measurements.md, ODE).
  int max_contacts = 8;

  /// dBodySetFiniteRotationMode(1) with no axis (ODE default 0: the infinitesimal quaternion
  /// update q += dt/2 w q, renormalised, which turns by 2 atan(w dt / 2) instead of w dt).
  /// Ours: on, exact rotation for the step's angular velocity. Measured: no difference in the
  /// probes' printed digits at dt = 1e-4 s (w dt <= 1e-4 rad: the tangent update's error
  /// (w dt)^3 / 12 is 1e-13 rad per step).
  bool finite_rotation = true;
  /// Cylinder only: complete dCollideCylinderPlane near upright (ODE has no such switch: false
  /// is its collider as it is). With the axis within about 4.5e-4 rad of the plane's normal
  /// (|cos(tilt) - 1| < 1e-7) ODE's collider takes its face branch, which makes no contact at
  /// all until the lower face's centre is under the plane: the rim sinks up to R sin(tilt)
  /// (1.1e-4 m for D = 0.5 m) unresisted, and a rocking cylinder falls freely through the
  /// cone at each pass near upright, then lands on the face's four points (measured, D = 0.5 m,
  /// H = 1.5 m, free rocking from 0.1 rad, rate after the first landing over the rate before:
  /// off 0.925 at dt 1e-5 s, on 0.849, the reference's 0.849; the tilt's error over 2 s at
  /// 1e-5 s: off 0.076 rad, on 1.2e-5 rad). Ours: on: in that cone the contacts are the lowest
  /// rim point (the
  /// formula of ODE's tilted branch, when it is on or under the plane) and the rim points 90,
  /// 180 and 270 degrees round from it that are under the plane; exactly upright, ODE's four
  /// points (then all at the face's depth). Outside the cone ODE's collider as it is.
  bool cylinder_upright_rim = true;
  /// Thickness of the ground box, m (the top face is y = 0).
  double ground_depth_m = 1.0;

  bool operator==(const OdeSettings&) const = default;
};

/// The [ode] table: every OdeSettings field, with ODE's own default beside ours.
const EngineSettingsSchema& OdeSettingsSchema();

/// The input of one ODE run: the common engine input (step, drive, base motion) and the settings.
using OdeRun = EngineRunInput<OdeSettings>;

/// Resolves the scene's [ode] table (SceneError naming FILE:LINE and the key for a bad value)
/// and samples the base motion on its step.
OdeRun MakeOdeRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s);

}  // namespace rockbench::ode
