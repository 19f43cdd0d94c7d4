#pragma once
/// What the MuJoCo worlds (the planar blocks, mujoco_world.h, and the cylinder,
/// mujoco_cylinder_world.h) share: the MJCF words of the settings, the contact's solref and
/// solimp at a step, the compilation of an MJCF string, and MuJoCo's warnings kept quiet.
#include <string>

#include "engines/mujoco/mujoco_settings.h"

struct mjModel_;

namespace rockbench::mujoco {

/// A number as MJCF text, to the last digit (%.17g).
std::string Num(double v);

/// The MJCF words of the integrator and the solver.
const char* MjcfIntegrator(Integrator i);
const char* MjcfSolver(Solver s);

/// A contact's solref (time constant s, damping ratio) and solimp (dmin, dmax, width m,
/// midpoint, power).
struct ContactParams {
  double solref[2];
  double solimp[5];
};

/// The contact's parameters at the step dt_s (s).
ContactParams ContactParamsOf(const MujocoSettings& s, double dt_s);

/// Throws std::invalid_argument ("mujoco: " + what) when !ok.
void Check(bool ok, const std::string& what);

/// Checks the stiff contact's solimp (a constant no key sets) against MuJoCo's ranges.
void CheckSolimp(const MujocoSettings& s);

/// MuJoCo's default warning handler prints to stdout and appends to MUJOCO_LOG.TXT in the
/// working directory; this drops the warnings (counted in mjData::warning, which the worlds
/// report), once, unless the program installed a handler of its own.
void InstallQuietWarningHandler();

/// Compiles an MJCF string (through a virtual file; serialised: mj_loadXML keeps the last
/// parsed model in a global). Throws std::runtime_error with MuJoCo's message when it does not
/// compile.
mjModel_* CompileMjcf(const std::string& xml);

}  // namespace rockbench::mujoco
