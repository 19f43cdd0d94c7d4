#pragma once
/// What DART's worlds of rockbench share, whatever they hold (the planar stack, dart_world.h; the
/// cylinder, dart_cylinder_world.h): the constraint solver and collision detector the [dart]
/// settings choose, with their LCP solves counted, and the process-wide contact parameters; the
/// world made with them, the input's check, a shape's contact coefficients, the step's counts
/// and the settings both worlds write.
#include <cstddef>
#include <cstdint>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/simulation/World.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "engines/common/engine_input.h"
#include "engines/dart/dart_settings.h"

namespace rockbench::dart_engine {

/// Counts of the boxed LCP solves of a world since its construction: the contact groups solved
/// (primary_calls), those the primary solver gave up on (primary_failures; with the PGS fallback
/// on, Dantzig stops at its first failed pivot), the fallback's solves and its reported
/// failures (PGS did not converge; DART uses its result anyway).
struct DartLcpCounts {
  std::int64_t primary_calls = 0, primary_failures = 0, fallback_calls = 0, fallback_failures = 0;
};

/// Sets the world's boxed LCP solvers (lcp_solver, pgs_fallback, pgs_iterations, counted into
/// *counts, which must outlive the world), its collision detector (collision; FCL with its
/// primitive shapes and DART's contact points) and the collision query's contact cap
/// (max_contacts). Returns the world's constraint solver; std::logic_error when it is not a
/// boxed LCP one.
dart::constraint::BoxedLcpConstraintSolver* ConfigureDartSolver(dart::simulation::World& world,
                                                                const DartSettings& settings,
                                                                DartLcpCounts* counts);

/// DART's contact parameters are static members of dart::constraint::ContactConstraint, shared by
/// every DART world of the process. A world takes them (with its settings' erp, error allowance,
/// max erv and cfm) for its lifetime: the first live world sets them; another one while it lives
/// must use the same values (std::invalid_argument otherwise). Thread-safe.
class DartContactParams {
 public:
  explicit DartContactParams(const DartSettings& settings);
  ~DartContactParams();
  DartContactParams(const DartContactParams&) = delete;
  DartContactParams& operator=(const DartContactParams&) = delete;

  /// The values in force (read back from DART), for summary.json's settings.
  static void Write(nlohmann::json* settings);
};

/// A world named `name` with the input's step, gravity `gravity_mps2` until the drive sets it,
/// and the settings' solver and collision detector (ConfigureDartSolver, counting into *counts).
/// Its constraint solver goes to *solver when that is not null.
dart::simulation::WorldPtr MakeDartWorld(const std::string& name, const EngineInput& input,
                                         const Eigen::Vector3d& gravity_mps2,
                                         const DartSettings& settings, DartLcpCounts* counts,
                                         dart::constraint::BoxedLcpConstraintSolver** solver);

/// Throws std::invalid_argument when the kinematic drive has no ground displacement samples at
/// n = 0..steps (the settings' ranges are the [dart] schema's, checked when the table was
/// resolved; the step is the input's, checked by MakeEngineInput).
void CheckDartInput(const EngineInput& input);

/// A shape's coefficients: friction (DART takes the smaller of a contact's two shapes') and
/// restitution (DART multiplies them).
void SetContactCoefficients(dart::dynamics::ShapeNode* node, double mu, double restitution);

/// A world's counts since construction: steps, the most contacts of a step, and its LCP solves.
struct DartStepCounts {
  std::int64_t steps = 0;
  std::size_t max_contacts = 0;
  DartLcpCounts lcp;

  /// After a World::step: one more step, and its contacts.
  void Count(const dart::simulation::World& world);
  /// For summary.json's "diagnostics": steps, max_contacts and the LCP solves' counts.
  nlohmann::json Diagnostics() const;
};

/// The settings both worlds write to summary.json: DART's version, drive, step and output
/// interval, the collision detector, the LCP solvers, restitution and friction with DART's
/// combination of restitution, the contact parameters in force (DartContactParams::Write),
/// the contact cap, the ground's depth, the kinematic high-pass and the integrator.
nlohmann::json CommonSettings(const EngineInput& input, const DartSettings& settings,
                              const dart::simulation::World& world);

}  // namespace rockbench::dart_engine
