#pragma once
/// The Siconos scene of the cylinder (shape "cylinder", issue 41): a NewtonEulerDS on the ground
/// plane with Coulomb contacts on its bottom rim, stepped by Moreau-Jean time stepping
/// (engines/siconos/siconos_cylinder_system.h), behind the CylinderWorld concept
/// (engines/common/cylinder_world.h).
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>

#include "engines/common/cylinder_world.h"
#include "engines/common/world_base.h"
#include "engines/siconos/siconos_settings.h"

namespace rockbench::siconos_engine {

class SiconosCylinderSystem;

/// The cylinder of CylinderBodyOf (mass and central inertia set explicitly) from
/// CylinderStartPose, on the plane z = 0 (world axes as rockbench's: +x horizontal, +y
/// transverse, +z up). Its contact is exact: kRimContacts points of the round bottom rim, the
/// lowest one and the others equally spaced from it, recomputed from the orientation at every
/// evaluation (no hull). The [siconos] settings as for blocks: theta, restitution, friction (the
/// scene's block1.friction when finite), solver (nsgs only: the 3-D frictional contact has no
/// LCP form), solver_tolerance, solver_max_iterations, lemke_fallback (here the nonsmooth
/// Newton solver, the 3-D problem's direct one), newton, activation_threshold. Keeps a
/// reference to `input`, which must outlive it. Throws std::invalid_argument for settings it
/// cannot take (naming the key).
class SiconosCylinderWorld : WorldBase<SiconosSettings> {
 public:
  SiconosCylinderWorld(const EngineInput& input, const SiconosSettings& settings);
  ~SiconosCylinderWorld();

  /// Sets the base motion for step n (from t_n to t_{n+1}). Inertial drive: the external force
  /// m (-a_x, -a_y, -(g + a_z)) of CylinderDriveAccel(n), constant over the step. Kinematic
  /// drive: the ground at u_n moving with (u_{n+1} - u_n) / dt during the step, the force
  /// m (0, 0, -g).
  void ApplyDrive(std::int64_t n);
  /// One step: TimeStepping::computeOneStep and nextStep.
  void Step();
  /// The pose after the last step relative to the base (kinematic drive: the ground's
  /// displacement and velocity subtracted); not finite once Siconos has failed (the monitor's
  /// non-finite stop).
  CylinderPose ReadPose() const;
  /// Settings in use, for summary.json.
  nlohmann::json Settings() const;
  /// Counts since construction, for summary.json's "diagnostics" (as SiconosWorld's).
  nlohmann::json Diagnostics() const;

 private:
  const CylinderBodyDef body_;
  double friction_ = 0.0;  // the rim's Coulomb coefficient in use
  bool failed_ = false;
  std::int64_t steps_done_ = 0;  // the pose is at t = steps_done_ * dt
  std::int64_t next_step_ = 0;   // the step ApplyDrive set up
  std::unique_ptr<SiconosCylinderSystem> sys_;
};

/// Runs a cylinder scene's input (RunCylinderWorld); a setting the cylinder cannot take is a
/// SceneError naming `scene_path`.
EngineResult SimulateCylinder(const std::string& scene_path, const EngineInput& input,
                              const SiconosSettings& settings);

}  // namespace rockbench::siconos_engine
