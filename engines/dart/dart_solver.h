#pragma once
/// What DART's worlds of rockbench share, whatever they hold (the planar stack, dart_world.h; the
/// cylinder, dart_cylinder_world.h): the constraint solver and collision detector the [dart]
/// settings choose, with their LCP solves counted, and the process-wide contact parameters.
#include <cstdint>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/simulation/World.hpp>
#include <nlohmann/json.hpp>

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

}  // namespace rockbench::dart_engine
