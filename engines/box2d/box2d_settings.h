#pragma once
/// Settings of the Box2D engine (Box2D 2.4.1, Debian's libbox2d-dev: a planar engine in single
/// precision). Defaults are ours, chosen for rocking blocks; Box2D's own defaults are given with
/// each field (b2FixtureDef: friction 0.2, restitution 0, restitution threshold 1 m/s, density 0;
/// b2BodyDef: allowSleep, no bullet; b2World: warm starting and continuous physics on, no
/// sub-stepping; the testbed's step 1/60 s with 8 velocity and 3 position iterations).
///
/// Box2D's length constants are compile-time, in metres (b2_common.h, b2_lengthUnitsPerMeter 1):
/// every polygon is rounded by a skin b2_polygonRadius = 2 b2_linearSlop = 0.01 m, the position
/// solver leaves b2_linearSlop = 0.005 m of penetration uncorrected and corrects the rest by
/// b2_baumgarte = 0.2 of it per iteration, at most b2_maxLinearCorrection = 0.2 m, and a body
/// moves at most b2_maxTranslation = 2 m in a step (its velocity is scaled down to that). For a
/// block of 0.1 m a 1 cm rounded corner is a different block: `length_scale` simulates the world
/// with every length multiplied by it (dynamic similarity, below), which shrinks all of these
/// against the blocks by the same factor. Box2D is single precision: its errors stop falling
/// below dt = 1e-4 s (docs/engines.md "Box2D").
#include <optional>
#include <string_view>

#include "engines/common/engine_input.h"
#include "scene/engine_settings.h"

namespace rockbench::box2d_engine {

/// The largest friction coefficient Box2D is given (a table's number is at most 1e6 anyway; a
/// scene's block friction above it is taken as 1e6): the contact solver bounds a friction
/// impulse by mu times the normal impulse in float, which must stay finite.
inline constexpr double kMaxFriction = 1e6;

/// The [box2d] settings besides the time step, which is EngineInput::time_step_s (b2World::Step
/// takes it as a float; Box2D's testbed uses 1/60 s).
struct Box2dSettings {
  /// Velocity iterations of the sequential-impulse solver per step (Box2D's testbed and manual:
  /// 8). Ours: 30, which matches the thesis stack's impacts without uplift (measurements:
  /// docs/engine-measurements.md, Box2D).
  int velocity_iterations = 30;
  /// Position (non-linear Gauss-Seidel) iterations per step, a maximum: Box2D stops early once
  /// every contact is within 3 b2_linearSlop (testbed and manual: 3).
  int position_iterations = 3;
  /// Coulomb friction coefficient of a contact whose scene coefficient is infinite (b2FixtureDef
  /// default 0.2; Box2D mixes two fixtures' values by sqrt(mu_a mu_b), which this adapter
  /// replaces by setting each contact's value in PreSolve). Box2D has no unbounded friction (the
  /// solver bounds the friction impulse by mu times the normal impulse), so ours is a large
  /// finite 10, as DART, MuJoCo and Siconos: the thesis stack needs |T|/N up to 1.28.
  double friction = 10.0;
  /// Restitution (b2FixtureDef default 0). Ours: 0, Housner's plastic impact at the landing
  /// corner (the energy lost follows from the geometry).
  double restitution = 0.0;
  /// Restitution threshold, m/s of the scene (b2FixtureDef default 1 m/s in Box2D's units, which
  /// is 1 / length_scale m/s of the scene): a contact approaching slower than this does not
  /// bounce. With restitution 0 it changes nothing (Box2D's velocity bias is -e v = 0 either
  /// way); ours keeps Box2D's number in the scene's units.
  double restitution_threshold_mps = 1.0;
  /// Every length of the world (block sizes, positions, gravity, base accelerations, velocities)
  /// is multiplied by this in Box2D, and poses and velocities are divided by it when read back;
  /// times, angles and angular velocities are unchanged (dynamic similarity: t ~ sqrt(L / g)
  /// holds when L and g scale alike), masses are the scene's, and moments of inertia scale as
  /// L^2. Box2D's own: 1 (no scaling). The skin, the slop and the position correction's cap are
  /// fixed in Box2D's metres, so in the scene's metres they are divided by length_scale: ours,
  /// 100, makes the rounding of a corner 0.1 mm. The price: a body moves at most
  /// b2_maxTranslation = 2 m of Box2D's per step, 2 / (length_scale dt) m/s of the scene
  /// (20 m/s at dt = 1e-4 s, 2 m/s at 1e-3 s, 0.12 m/s at 1/60 s with ours); summary.json's
  /// diagnostics count the steps where that cap acted. Ours: 1000. The skin costs about
  /// 0.01 m / (length_scale b) rad on a block of half width b; at 10000 a float coordinate's ulp
  /// nears the slop (measurements: docs/engine-measurements.md, Box2D).
  double length_scale = 1000.0;
  /// Warm starting of the contact impulses from the previous step (b2World default on).
  bool warm_starting = true;
  /// Continuous collision against the static (or kinematic) ground: time of impact and sub-steps
  /// (b2World default on). Ours: on, Box2D's.
  bool continuous = true;
  /// Blocks are bullets (b2BodyDef default false): continuous collision between dynamic bodies
  /// too. Ours: off, Box2D's.
  bool bullet = false;
  /// Thickness of the ground box, m (the top face is y = 0).
  double ground_depth_m = 1.0;

  bool operator==(const Box2dSettings&) const = default;
};

/// The [box2d] table: every Box2dSettings field, with Box2D's own default beside ours.
const EngineSettingsSchema& Box2dSettingsSchema();

/// The input of one Box2D run: the common engine input (step, drive, base motion) and the
/// settings.
using Box2dRun = EngineRunInput<Box2dSettings>;

/// Resolves the scene's [box2d] table (SceneError naming FILE:LINE and the key for a bad value)
/// and samples the base motion on its step.
Box2dRun MakeBox2dRun(const Scene& scene, const GroundMotion& motion, double stop_at_rest_after_s);

}  // namespace rockbench::box2d_engine
