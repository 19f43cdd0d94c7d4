#include "engines/siconos/siconos_world_parts.h"

#include <algorithm>
#include <cmath>

namespace rockbench::siconos_engine {

nlohmann::json CommonSettings(const EngineInput& input, const SiconosSettings& s, bool kinematic) {
  nlohmann::json j;
  j["siconos_version"] = SiconosVersionString();
  j["drive"] = kinematic ? "kinematic" : "inertial";
  j["time_step_s"] = input.time_step_s;
  j["output_interval_s"] = input.run.output_interval_s;
  j["substeps_per_sample"] =
      std::max(1.0, std::round(input.run.output_interval_s / input.time_step_s));
  j["theta"] = s.theta;
  j["restitution"] = s.restitution;
  j["friction"] = s.friction;
  j["solver_tolerance"] = s.solver_tolerance;
  j["solver_max_iterations"] = s.solver_max_iterations;
  j["newton"] = s.newton_linear ? "linear (SICONOS_TS_LINEAR)" : "nonlinear (SICONOS_TS_NONLINEAR)";
  j["kinematic_highpass_hz"] = input.kinematic_highpass_hz;
  j["integrator"] = "Moreau-Jean time stepping (TimeStepping + MoreauJeanOSI)";
  return j;
}

nlohmann::json CountersJson(const SiconosCounters& c, const std::string& siconos_error) {
  nlohmann::json j;
  j["steps"] = c.steps;
  j["solver_failures"] = c.solver_failures;
  j["fallback_solves"] = c.fallback_solves;
  j["fallback_failures"] = c.fallback_failures;
  j["newton_iterations"] = c.newton_iterations;
  j["max_newton_iterations_per_step"] = c.max_newton_iterations;
  j["max_active_contacts"] = c.max_active_contacts;
  j["solves"] = c.solves;
  j["solver_iterations"] = c.solver_iterations;
  j["max_solver_iterations"] = c.max_solver_iterations;
  j["siconos_error"] = siconos_error;
  return j;
}

}  // namespace rockbench::siconos_engine
