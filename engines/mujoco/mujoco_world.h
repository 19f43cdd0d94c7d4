#pragma once
/// The MuJoCo (2.2.2) scene of one block or two stacked blocks, the counterpart of Bullet's
/// RockingWorld (engines/bullet/rocking_world.h) with the same semantics.
///
/// The model is an MJCF string compiled by mj_loadXML: the motion plane is MuJoCo's x-y plane
/// (x right, y up, as our readout) with gravity along -y; the ground is a plane geom whose
/// normal is +y through the origin (top face y = 0); each block is a box body, child of the
/// world body, held in the plane by three joints (slide x, slide y, hinge about z, in that
/// order, all at the mass centre), so qpos = (x, y, phi) and qvel = (vx, vy, w) of its mass
/// centre exactly, and nothing moves out of the plane.
///
/// Thread safety: every world owns its mjModel and mjData; stepping different worlds on
/// different threads is safe. Model compilation (mj_loadXML keeps the last parsed model in a
/// global) is serialised by a mutex. A MuJoCo error (mju_error: out of stack memory, which the
/// sizes here rule out) would end the process through MuJoCo's default handler.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/mujoco/mujoco_settings.h"

// MuJoCo's types, declared here so that users of this header need not see mujoco.h.
struct mjModel_;
struct mjData_;

namespace rockbench::mujoco {

class MujocoSim;

/// A MuJoCo world holding a ground plane and N box blocks placed by the pivot chain, children
/// of the world body. With three or more blocks only neighbours collide (block 1 and the
/// ground, block k and block k - 1: every other pair is a <contact><exclude>). Keeps a
/// reference to `input`, which must outlive it.
class MujocoWorld {
 public:
  /// Builds the model. Throws std::invalid_argument for the kinematic drive (MuJoCo's mocap
  /// bodies have no velocity in the contact equations: see mujoco_world.cc), for settings out
  /// of range, or when settings.time_step_s differs from input.time_step_s; std::runtime_error
  /// when MuJoCo does not compile the model.
  MujocoWorld(const EngineInput& input, const MujocoSettings& settings);
  ~MujocoWorld();
  MujocoWorld(const MujocoWorld&) = delete;
  MujocoWorld& operator=(const MujocoWorld&) = delete;

  /// Sets the base motion for step n (from t_n to t_{n+1}): gravity
  /// (-xg''(t_n), -(g + yg''(t_n)), 0), the exact equivalent of a translating base.
  void ApplyDrive(std::int64_t n);
  /// One fixed step: mj_step (collision and constraint solve at the state of t_n, then the
  /// integrator). A step in which MuJoCo found a bad number (and, as it does, reset the
  /// simulation) leaves the world blown up: Read then returns NaN, which the monitor reports as
  /// a blow-up, and further steps do nothing.
  void Step();
  /// The state after n steps, read from qpos/qvel (mass centre, angle, velocities).
  StepReadout Read(std::int64_t n) const;

  /// Settings in use (ours and the MuJoCo values they set) for summary.json.
  nlohmann::json Settings() const;
  /// What MuJoCo reported during the run so far: warning counts (contact or constraint buffer
  /// full, bad numbers), the largest number of contacts and of solver iterations in a step.
  nlohmann::json Diagnostics() const;

  /// The MJCF text the model was compiled from.
  const std::string& xml() const { return xml_; }
  const mjModel_* model() const;
  const mjData_* data() const;

 private:
  const EngineInput& in_;
  MujocoSettings s_;
  double dt_ = 0.0;
  std::string xml_;
  std::unique_ptr<MujocoSim> sim_;  // the model, its data and its step (mujoco_world_parts.h)
  mjModel_* m_ = nullptr;           // sim_'s
  mjData_* d_ = nullptr;            // sim_'s
  std::vector<int> qpos_, qvel_;    // addresses of (x, y, phi) per block, bottom first
};

}  // namespace rockbench::mujoco
