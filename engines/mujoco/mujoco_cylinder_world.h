#pragma once
/// The cylinder (shape "cylinder", engines/common/cylinder_world.h) in MuJoCo 2.2.2: a body with
/// a free joint carrying MuJoCo's own cylinder geom, on a ground plane z = 0 (MuJoCo's up is +z,
/// as ours: no axis mapping).
///
/// MuJoCo collides a cylinder with a plane in closed form (mjc_PlaneCylinder, not the convex
/// libccd path, so the multiccd flag plays no part): the first contact is the exact lowest rim
/// point, so the contact of a cylinder rocking or rolling on its rim is a point of the true
/// circle, whatever the azimuth; a second one is the rim point above it on the other face (the
/// cylinder on its side); and when the bottom face comes within the contact's reach, two more
/// at +-120 degrees from the lowest rim point (an equilateral triangle inscribed in the bottom
/// rim, with the lowest point). So the face stands on three rim points, one of them always on
/// the side it leans to: its edge in the direction of tipping is the true rim (the onset's lever
/// is R). A landing face meets the ground on the two triangle points (half a radius behind the
/// centre) only in the step around tilt 0; once the tilt has changed side, the lowest
/// point is the far rim point (one step with three contacts per landing of free rocking, at
/// steps of 1e-3 to 1e-5 s). An N-sided mesh hull (plane-convex: the deepest vertex and up to 3
/// more) would follow free wobbling several times worse than this geom even at N = 128, and a
/// hull's rocking is exact only in the planes of its vertices (measured:
/// docs/engine-measurements.md, MuJoCo).
///
/// The base motion is the inertial drive (gravity (-a_x, -a_y, -(g + a_z)) each step); the
/// kinematic drive is refused, as for blocks (mujoco_world.cc: a mocap ground has no velocity in
/// the contact equations). Mass and central inertia are CylinderBodyOf's, set explicitly (the
/// compiler does not compute them from the geom). The contact, solver and friction settings are
/// the [mujoco] table's, as for blocks; restitution is that of the stiff contact (no
/// restitution parameter: plastic).
///
/// Thread safety: as MujocoWorld (each world owns its model and data; compilation serialised).
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "engines/common/cylinder_world.h"
#include "engines/mujoco/mujoco_settings.h"

struct mjModel_;
struct mjData_;

namespace rockbench::mujoco {

class MujocoSim;

class MujocoCylinderWorld {
 public:
  /// Builds the model at CylinderStartPose. Throws std::invalid_argument for the kinematic
  /// drive or a stiff solimp out of MuJoCo's range, std::runtime_error when MuJoCo does not
  /// compile the model. Keeps a reference to `input`, which must outlive it.
  MujocoCylinderWorld(const EngineInput& input, const MujocoSettings& settings);
  ~MujocoCylinderWorld();
  MujocoCylinderWorld(const MujocoCylinderWorld&) = delete;
  MujocoCylinderWorld& operator=(const MujocoCylinderWorld&) = delete;

  /// Sets the base motion for step n: gravity (-a_x, -a_y, -(g + a_z)) with a =
  /// CylinderDriveAccel(input, n), the exact equivalent of a translating base.
  void ApplyDrive(std::int64_t n);
  /// One fixed step (mj_step). A step in which MuJoCo found a bad number (and reset the
  /// simulation) leaves the world blown up: ReadPose then returns NaN, and further steps do
  /// nothing.
  void Step();
  /// The pose after the last step, from qpos and qvel (the ground does not move: relative to the
  /// base as it is).
  CylinderPose ReadPose() const;

  /// Settings in use (ours and the MuJoCo values they set), summary.json's "settings".
  nlohmann::json Settings() const;
  /// What MuJoCo reported during the run: warning counts, the largest number of contacts and of
  /// solver iterations in a step, and the steps that had 1, 2, 3 and 4 contacts.
  nlohmann::json Diagnostics() const;

  const std::string& xml() const { return xml_; }

 private:
  const EngineInput& in_;
  MujocoSettings s_;
  std::string xml_;
  std::unique_ptr<MujocoSim> sim_;  // the model, its data and its step (mujoco_world_parts.h)
  mjModel_* m_ = nullptr;           // sim_'s
  mjData_* d_ = nullptr;            // sim_'s
  std::int64_t steps_with_contacts_[5] = {0, 0, 0, 0, 0};  // 0, 1, 2, 3, 4 or more
};

}  // namespace rockbench::mujoco
