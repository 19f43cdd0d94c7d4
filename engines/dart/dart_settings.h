#pragma once
/// Settings of the DART engine (DART 6.12, Debian libdart-dev). Every field says its unit, DART's
/// own default and why ours differs. The namespace is not `dart`, which is DART's own.
///
/// The measurements behind ours are in docs/engine-measurements.md, DART.
#include <cstdint>
#include <string>

#include "engines/common/engine_input.h"
#include "scene/engine_settings.h"

namespace rockbench::dart_engine {

/// DART's collision detectors that handle box-box pairs and are installed with libdart-dev.
/// (DART's Bullet and ODE detectors are separate packages, libdart-collision-bullet-dev and
/// libdart-collision-ode-dev, not installed here: not offered.)
/// The cylinder (dart_cylinder_world.h) takes its shape from the detector: DART's own has no
/// cylinder (a 64-sided prism of boxes stands for it); FCL meshes DART's CylinderShape with 16
/// slices.
enum class DartCollision {
  /// dart::collision::DARTCollisionDetector: ODE's dBoxBox clipping (a corner edge on a face
  /// gives its 2 end points, a face on a face 4).
  kDart,
  /// dart::collision::FCLCollisionDetector with primitive boxes (FCL 0.7's box-box) and DART's
  /// contact-point computation.
  kFcl,
};

/// DART's boxed-LCP solvers for the contact constraints.
enum class DartLcpSolver {
  /// dart::constraint::DantzigBoxedLcpSolver (ODE's Dantzig pivoting).
  kDantzig,
  /// dart::constraint::PgsBoxedLcpSolver (projected Gauss-Seidel, iterative).
  kPgs,
};

/// "dart" / "fcl"; "dantzig" / "pgs".
const char* DartCollisionName(DartCollision c);
const char* DartLcpSolverName(DartLcpSolver s);

/// The [dart] settings besides the time step, which is EngineInput::time_step_s (DART's default
/// 1e-3 s, World::setTimeStep; ours is the project's 1e-4 s: DART is first order in dt here, a
/// landing corner being seen once it penetrates and the semi-implicit Euler step leading the
/// angle by half a step; measured: docs/engine-measurements.md, DART).
struct DartSettings {
  /// Collision detector. DART's default: FCL. Ours: DART's own, whose box-box gives exactly the
  /// corner-edge and face contacts rocking needs; FCL (primitive boxes) is no more accurate
  /// (measured: docs/engine-measurements.md, DART).
  DartCollision collision = DartCollision::kDart;

  /// Boxed LCP solver. DART's default: Dantzig, with PGS as a fallback. Ours: the same.
  /// Dantzig alone is not usable on the stack: the planar joints leave the contacts'
  /// out-of-plane friction rows empty and make the rows of the points at z = +-depth/2 equal,
  /// and Dantzig gives up on, or returns NaN for, many of the stack's steps (DART then zeroes
  /// the impulses). Measured: docs/engine-measurements.md, DART.
  DartLcpSolver lcp_solver = DartLcpSolver::kDantzig;
  /// Whether PGS solves a contact group when Dantzig fails (DART runs Dantzig with early
  /// termination when a fallback is set). DART's default: yes. Ours: yes (see lcp_solver).
  bool pgs_fallback = true;
  /// PGS iterations (PGS as the solver or the fallback). DART's default 30. Ours: the same
  /// (more change nothing: docs/engine-measurements.md, DART).
  int pgs_iterations = 30;

  /// Restitution coefficient of every body (DART uses the product of the two bodies'). DART's
  /// default 0. Ours: 0; the impact loss is the rigid-body one (Housner's), no bounce.
  double restitution = 0.0;
  /// Friction coefficient of every body (DART uses the smaller of the two bodies'; the cone is
  /// DART's 2-direction pyramid). DART's default 1. Ours: 10: the model assumes no sliding, and
  /// the thesis stack needs |T|/N up to 1.28 at the interface (reference's
  /// friction_required_interface), and with DART's 1 block 2 slides (measured:
  /// docs/engine-measurements.md, DART).
  double friction = 10.0;

  /// Contact error reduction parameter: a penetration d deeper than the allowance is pushed out
  /// with the velocity target min(erp * (d - allowance) / dt, max_erv) (Baumgarte;
  /// ContactConstraint::setErrorReductionParameter, process-wide). DART's default 0.01. Ours:
  /// the same. 0 leaves every landing corner's penetration in place; larger values are no
  /// better (measured: docs/engine-measurements.md, DART).
  double erp = 0.01;
  /// Penetration tolerated without correction, m (ContactConstraint::setErrorAllowance,
  /// process-wide). DART's default 0. Ours: 0: an allowance lets the corners rest that deep,
  /// which moves the pivots by as much.
  double error_allowance_m = 0.0;
  /// Cap on the penetration-correction velocity, m/s
  /// (ContactConstraint::setMaxErrorReductionVelocity, process-wide). DART's default 1e-3 m/s.
  /// Ours: the same. A correction velocity v launches a block v^2 / 2g high: 5e-8 m at 1e-3 m/s,
  /// far below the monitor's 1e-5 m uplift tolerance (a larger cap: docs/engine-measurements.md,
  /// DART).
  double max_erv_mps = 1e-3;
  /// Constraint force mixing, relative: DART multiplies each diagonal entry of the LCP matrix by
  /// (1 + cfm) (ContactConstraint::setConstraintForceMixing, process-wide; DART refuses less
  /// than 1e-9, so the schema does). DART's default 1e-5. Ours: the same
  /// (docs/engine-measurements.md, DART).
  double cfm = 1e-5;
  /// Largest number of contacts the collision query returns per step, over all pairs
  /// (CollisionOption::maxNumContacts; DART 6.12 has no per-pair limit). DART's default 1000.
  /// Ours: the same; box-box gives at most 4 per pair.
  int max_contacts = 1000;

  /// Ground box thickness, m (the ground is a box whose top face is y = 0; as Bullet's).
  double ground_depth_m = 1.0;

  bool operator==(const DartSettings&) const = default;
};

/// The [dart] table: every DartSettings field, with DART's own default beside ours.
const EngineSettingsSchema& DartSettingsSchema();

/// The input of one DART run: the common engine input (step, drive, base motion) and the
/// settings.
using DartRun = EngineRunInput<DartSettings>;

/// Resolves the scene's [dart] table (SceneError naming FILE:LINE and the key for a bad value)
/// and samples the base motion on its step.
DartRun MakeDartRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s);

}  // namespace rockbench::dart_engine
