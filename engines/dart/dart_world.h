#pragma once
/// The DART scene of the stack of N blocks: the same mechanics as Bullet's RockingWorld
/// (engines/bullet/rocking_world.h) with DART 6.12's skeletons, boxed-LCP contacts and
/// collision detectors.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/dart/dart_settings.h"

namespace rockbench::dart_engine {

/// A DART world holding a ground box (top face y = 0; an immobile skeleton, moved by hand for
/// the kinematic drive) and N box blocks, each its own skeleton held in the x-y plane by a
/// PlanarJoint to the world, placed by the pivot chain. With three or more blocks only
/// neighbours collide (the collision filter's blacklist holds every other pair). Keeps a reference
/// to `input`, which must outlive it.
///
/// DART's contact parameters (erp, error allowance, max erv, cfm) are static members of
/// dart::constraint::ContactConstraint, shared by every DART world of the process: the
/// constructor sets them and throws std::invalid_argument when another live DartWorld uses
/// different values.
class DartWorld {
 public:
  DartWorld(const EngineInput& input, const DartSettings& settings);
  ~DartWorld();
  DartWorld(const DartWorld&) = delete;
  DartWorld& operator=(const DartWorld&) = delete;

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: gravity
  /// (-xg''(t_n), -(g + yg''(t_n)), 0). Kinematic drive: the ground at u(t_n) moving with
  /// (u_{n+1} - u_n) / dt during the step.
  void ApplyDrive(std::int64_t n);
  /// One fixed step (World::step: semi-implicit Euler, contacts by one boxed LCP on velocities).
  void Step();
  /// The state after n steps, read from the bodies' world transforms and velocities.
  StepReadout Read(std::int64_t n) const;

  /// Settings in use (ours and the DART values they set) for summary.json.
  nlohmann::json Settings() const;

  /// Contacts found by the last step's collision query (all pairs).
  std::size_t LastContactCount() const;
  /// Counts since construction, for summary.json: steps, max_contacts (per step, all pairs),
  /// lcp_solves (contact groups solved), lcp_primary_failures (Dantzig gave up: with the PGS
  /// fallback on, Dantzig stops at its first failed pivot), lcp_fallback_solves,
  /// lcp_fallback_failures (PGS reported no convergence; DART uses its result anyway).
  nlohmann::json Diagnostics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbench::dart_engine
