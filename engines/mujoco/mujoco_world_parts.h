#pragma once
/// What the MuJoCo worlds share beyond the MJCF words (mujoco_mjcf.h), whatever they hold (the
/// planar stack, MujocoWorld in mujoco_world.h; the cylinder, MujocoCylinderWorld in
/// mujoco_cylinder_world.h): the parts of the MJCF text both write alike, the compiled model
/// and its data with the step and its blow-up, and the settings and diagnostics both write.
#include <nlohmann/json.hpp>
#include <string>

#include "engines/common/engine_input.h"
#include "engines/mujoco/mujoco_mjcf.h"
#include "engines/mujoco/mujoco_settings.h"

struct mjModel_;
struct mjData_;

namespace rockbench::mujoco {

/// The solref and solimp attributes of a contact.
std::string ContactAttributes(const ContactParams& c);

/// The <option> line: the input's step, `gravity` (the MJCF words of the gravity vector,
/// m/s^2), and the [mujoco] table's integrator, solver, iterations, tolerance, cone, impratio
/// and noslip settings.
std::string OptionMjcf(const EngineInput& input, const MujocoSettings& s,
                       const std::string& gravity);

/// The <default> geom line: condim 3, the table's friction (torsional 0.005, rolling 1e-4),
/// margin and gap 0, the contact's solref and solimp.
std::string GeomDefaultMjcf(const MujocoSettings& s, const ContactParams& c);

/// Friction from the scene between two bodies: their dynamic pair excluded (MuJoCo would take
/// the larger of the two geoms' coefficients) and an explicit pair of their geoms with exactly
/// `mu` (condim 3; at 0 a frictionless pair, condim 1: MuJoCo's friction is at least mjMINMU),
/// the contact's solref and solimp, margin and gap 0.
std::string SceneFrictionPairMjcf(const std::string& lower_body, const std::string& upper_body,
                                  const std::string& lower_geom, const std::string& upper_geom,
                                  double mu, const ContactParams& c);

/// A compiled model and its data, stepped by mj_step. A step in which MuJoCo found a bad number
/// (and, as it does, reset the simulation) leaves it blown up: further steps do nothing.
class MujocoSim {
 public:
  /// Compiles `xml` (CompileMjcf) and makes its data; std::runtime_error when either fails.
  explicit MujocoSim(const std::string& xml);
  ~MujocoSim();
  MujocoSim(const MujocoSim&) = delete;
  MujocoSim& operator=(const MujocoSim&) = delete;

  mjModel_* m() const { return m_; }
  mjData_* d() const { return d_; }
  bool blown_up() const { return blown_up_; }

  /// One mj_step unless blown up (then false): counts the contacts (found at the state before
  /// the step) and solver iterations, and sees whether MuJoCo reset the simulation.
  bool Step();
  /// MuJoCo's warning counts (contact or constraint buffer full, bad numbers), the largest
  /// number of contacts and of solver iterations in a step, and whether it blew up.
  nlohmann::json Diagnostics() const;

 private:
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  bool blown_up_ = false;
  int max_contacts_ = 0, max_iterations_ = 0;
};

/// The settings both worlds write to summary.json: MuJoCo's version, the drive (inertial), the
/// step and output interval, the contact's model, solref and solimp, the solver's, integrator's,
/// cone's, friction's and noslip's keys, margin, and whether refsafe and warm start are on.
nlohmann::json CommonSettings(const EngineInput& input, const MujocoSettings& s, const mjModel_* m);

}  // namespace rockbench::mujoco
