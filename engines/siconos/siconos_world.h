#pragma once
/// The Siconos scene of the two stacked blocks: the blocks as Lagrangian dynamical systems, a
/// unilateral contact with Coulomb friction at each bottom corner, stepped by Siconos's
/// nonsmooth Moreau-Jean time stepping (engines/siconos/siconos_system.h).
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/common/world_base.h"
#include "engines/siconos/siconos_settings.h"

namespace rockbench::siconos_engine {

class SiconosSystem;

/// The blocks placed by the pivot chain, each a LagrangianLinearTIDS (x, y, phi), with two
/// corner contacts per block: block 1's bottom corners on the ground (top face y = 0), block
/// k's on block k - 1's top face (only neighbours meet). One or two blocks: a stack of more is
/// refused (siconos_world.cc says why). Keeps a reference to `input`, which must
/// outlive it. Throws std::invalid_argument for settings it cannot take (naming the key).
class SiconosWorld : WorldBase<SiconosSettings> {
 public:
  SiconosWorld(const EngineInput& input, const SiconosSettings& settings);
  ~SiconosWorld();

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: each block's
  /// external force m (-xg''(t_n), -(g + yg''(t_n))), constant over the step (a
  /// LagrangianLinearTIDS's constant F_ext enters both theta-weighted ends of the step).
  /// Kinematic drive: the ground at u(t_n) moving with (u_{n+1} - u_n) / dt during the step.
  void ApplyDrive(std::int64_t n);
  /// One step: TimeStepping::computeOneStep and nextStep.
  void Step();
  /// The state after n steps; non-finite once Siconos has failed (the monitor's blow-up).
  StepReadout Read(std::int64_t n) const;

  /// Settings in use, for summary.json.
  nlohmann::json Settings() const;
  /// Counts since construction, for summary.json: steps, solver_failures (steps whose numerics
  /// solver reported no solution), fallback_solves and fallback_failures (Lemke after NSGS),
  /// newton_iterations (total and per step at most), max_active_contacts (index set 1), solves,
  /// solver_iterations (all solves) and max_solver_iterations, siconos_error (the exception that
  /// stopped the run).
  nlohmann::json Diagnostics() const;

 private:
  bool failed_ = false;
  std::unique_ptr<SiconosSystem> sys_;
};

}  // namespace rockbench::siconos_engine
