#pragma once
/// The Box2D scene of N stacked blocks: the same semantics as ODE's OdeWorld
/// (engines/ode/ode_world.h), so that the Monitor reads both alike. Box2D is planar: no
/// out-of-plane motion to constrain.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engines/box2d/box2d_settings.h"
#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/common/world_base.h"

// Box2D's types, declared here so that this header does not pull in Box2D.
class b2World;
class b2Body;

namespace rockbench::box2d_engine {

/// A Box2D world holding a static (inertial drive) or kinematic (kinematic drive) ground box and
/// N box blocks placed by the pivot chain (PlaceStack), all lengths multiplied by
/// Box2dSettings::length_scale (s below). Contacts only between neighbours (block 1 - ground,
/// block k - block k - 1; with two blocks also block 2 - ground, as ODE), by a contact filter;
/// a contact's friction is set in PreSolve to its interface's coefficient (InterfaceFriction).
///
/// Box2D rounds every polygon by its skin r = b2_polygonRadius (0.01 m of Box2D's, r / s of the
/// scene) and keeps touching shapes' skins in contact. Each shape here is the block (or the
/// ground) shrunk by r on every side, so that its skin's outline is the block's: the faces are
/// where the model has them and a resting block sits on the ground, not r above it; the corners
/// are rounded with radius r, and a face contact's two points lie r inside its corners.
///
/// Threads: a b2World is self-contained. Box2D 2.4's only process-wide state is the statistics
/// counters of its distance and time-of-impact routines (b2_gjkCalls, b2_toiCalls, ...), which it
/// writes and never reads for a result. One world must not be used by two threads at once.
class Box2dWorld : WorldBase<Box2dSettings> {
 public:
  /// Throws std::invalid_argument for a block too small for the skin (a half size of at most
  /// b2_polygonRadius / s) or an input that does not fit the drive.
  Box2dWorld(const EngineInput& input, const Box2dSettings& settings);
  ~Box2dWorld();

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: gravity
  /// s (-xg''(t_n), -(g + yg''(t_n))). Kinematic drive: the ground at s u(t_n) moving with
  /// s (u_{n+1} - u_n) / dt during the step. A value beyond the range of a float (Box2D's) is
  /// not given to Box2D: the run's next step is an engine fault (see Step).
  void ApplyDrive(std::int64_t n);
  /// One fixed step: b2World::Step with the settings' iterations. After an engine fault (a base
  /// motion beyond float range) no step is taken: StepReadout::engine_fault says why, and the
  /// monitor ends the run there (status non_finite).
  void Step();
  /// The state after n steps, read from the bodies (origin at the block's centre) and divided by
  /// the length scale.
  StepReadout Read(std::int64_t n) const;
  /// Settings in use (ours and the Box2D values they set) for summary.json.
  nlohmann::json Settings() const;
  /// What Box2D did of note in the run, for summary.json: the steps at which a block's velocity
  /// was capped by b2_maxTranslation (2 m of Box2D's per step).
  nlohmann::json Diagnostics() const;

 private:
  struct Callbacks;  // the contact filter and listener (box2d_world.cc)

  double dt_ = 0.0;
  double scale_ = 1.0;              // Box2D metres per metre of the scene
  double ground_half_depth_ = 0.0;  // Box2D's metres
  // Where Box2D's origin is in the scaled base frame (kinematic drive: it follows the ground;
  // inertial: zero), Box2D's metres.
  double origin_x_ = 0.0, origin_y_ = 0.0;
  std::unique_ptr<b2World> world_;
  std::unique_ptr<Callbacks> callbacks_;
  b2Body* ground_ = nullptr;
  std::vector<b2Body*> bodies_;  // per block, bottom first
  // Steps at which a block reached b2_maxTranslation, and the first one's time.
  std::int64_t capped_steps_ = 0;
  double first_capped_t_s_ = -1.0;
  std::int64_t steps_ = 0;
  // Why the next step cannot be taken (see ApplyDrive); empty: it can.
  std::string fault_;
};

}  // namespace rockbench::box2d_engine
