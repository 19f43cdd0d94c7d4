#pragma once
/// What the Siconos worlds share, whatever they hold (the planar stack, SiconosWorld in
/// siconos_world.h; the cylinder, SiconosCylinderWorld in siconos_cylinder_world.h): the
/// [siconos] settings of the time stepping as both systems' configurations take them, the
/// settings both write to summary.json, and the diagnostics of a system's counters.
#include <nlohmann/json.hpp>
#include <string>

#include "engines/common/engine_input.h"
#include "engines/siconos/siconos_settings.h"
#include "engines/siconos/siconos_system.h"

namespace rockbench::siconos_engine {

/// Copies the time stepping's settings into a system's configuration (SiconosSystemConfig or
/// SiconosCylinderConfig): the input's step, theta, restitution, the numerics solver, its
/// tolerance and iteration cap, the Newton loop, the activation threshold, and whether the
/// ground moves (the kinematic drive). Friction and the fallback solver are the caller's.
template <typename Config>
void SetTimeStepping(const EngineInput& input, const SiconosSettings& s, bool kinematic,
                     Config* c) {
  c->time_step_s = input.time_step_s;
  c->theta = s.theta;
  c->restitution = s.restitution;
  c->solver = s.solver;
  c->solver_tolerance = s.solver_tolerance;
  c->solver_max_iterations = s.solver_max_iterations;
  c->newton_linear = s.newton_linear;
  c->activation_threshold_m = s.activation_threshold_m;
  c->moving_ground = kinematic;
}

/// The settings both worlds write to summary.json: Siconos's version, drive, steps, theta,
/// restitution, friction, the solver's tolerance and iteration cap, the Newton loop, the
/// kinematic high-pass and the integrator. The solver's name, its fallback and the contact are
/// the caller's.
nlohmann::json CommonSettings(const EngineInput& input, const SiconosSettings& s, bool kinematic);

/// A system's counts since construction and the exception that stopped its run, for
/// summary.json's "diagnostics" (SiconosWorld::Diagnostics' keys).
nlohmann::json CountersJson(const SiconosCounters& c, const std::string& siconos_error);

}  // namespace rockbench::siconos_engine
