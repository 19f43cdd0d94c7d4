#pragma once
/// A cylinder's engine run (shape "cylinder", docs/three-d.md), whatever the engine: the body it
/// builds and the pose and velocity it starts from, the base motion of each step in three
/// components, and the run loop that reads the body back as the cylinder's state
/// (scene/cylinder_state.h) and watches its rim (slip, uplift, penetration) until the end or
/// the overturn. World axes here: +x along [base.horizontal], +y along [base.transverse], +z up;
/// an engine whose up axis is another maps them in its world.
#include <chrono>
#include <concepts>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "engine/engine.h"
#include "engines/common/engine_input.h"
#include "scene/cylinder_state.h"
#include "scene/history.h"
#include "util/stop_request.h"

namespace rockbench {

/// The cylinder an engine builds: solid, uniform density.
struct CylinderBodyDef {
  double radius_m = 0.0, half_height_m = 0.0, mass_kg = 0.0;
  double inertia_transverse_kgm2 = 0.0;  ///< m (3 R^2 + H^2) / 12, about a central diameter
  double inertia_axial_kgm2 = 0.0;       ///< m R^2 / 2
  double friction = 0.0;  ///< the scene's block1.friction (infinite: the engine's own value)
};
CylinderBodyDef CylinderBodyOf(const EngineInput& input);

/// A pose and velocity in the world (z up): the centre (m), the rotation body -> world
/// (row-major, body z the axis), the centre's velocity (m/s) and the angular velocity (rad/s).
/// Positions and velocities relative to the base's frame for the run loop; an engine adds the
/// base's displacement (CylinderBaseDisplacement) where its ground moves.
struct CylinderPose {
  Vec3d centre_m{};
  Mat3d rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3d velocity_mps{};
  Vec3d omega_radps{};
  /// Not empty: the engine refused its step (its next state would not be finite, or it would
  /// abort on it), and why; the monitor ends the run non_finite with this as its detail, as
  /// StepReadout::engine_fault does for planar blocks.
  std::string engine_fault;
};

/// The scene's initial state as a pose: leaning at its tilt and azimuth on the rim point on that
/// side (the contact at (R cos azimuth, R sin azimuth, 0) when it stood upright at the origin),
/// rolling at its rates without slip.
CylinderPose CylinderStartPose(const EngineInput& input);

/// The base acceleration during step n (inertial drive), world (x, y transverse, z up), m/s^2.
Vec3d CylinderDriveAccel(const EngineInput& input, std::int64_t n);
/// The base displacement at t_n (kinematic drive), world, m (n = 0..steps).
Vec3d CylinderBaseDisplacement(const EngineInput& input, std::int64_t n);
/// The base velocity before step 0 (kinematic drive), world, m/s.
Vec3d CylinderBaseVelocityBefore(const EngineInput& input);
/// The base velocity in the step that ended at t_n, (u_n - u_(n-1)) / dt (kinematic drive;
/// CylinderBaseVelocityBefore for n = 0), world, m/s.
Vec3d CylinderBaseVelocityAfter(const EngineInput& input, std::int64_t n);

/// What the run loop needs of an engine's cylinder world:
/// - ApplyDrive(n): sets the base motion for step n (CylinderDriveAccel or the ground path);
/// - Step(): takes that one step;
/// - ReadPose(): the body's pose after the last step (or the initial one), RELATIVE TO THE BASE
///   (an engine with a moving ground subtracts CylinderBaseDisplacement and the base velocity);
/// - Settings(): the settings in use, summary.json's "settings".
template <typename World>
concept CylinderWorld = requires(World& world, const World& read_only, std::int64_t n) {
  world.ApplyDrive(n);
  world.Step();
  { read_only.ReadPose() } -> std::same_as<CylinderPose>;
  { read_only.Settings() } -> std::convertible_to<nlohmann::json>;
};

/// Thresholds of the cylinder's monitor.
struct CylinderMonitorConfig {
  /// On the rim once the tilt exceeds tilt_enter_rad; back on the face below tilt_leave_rad
  /// (hysteresis above the engines' noise, as the planar monitor's).
  double tilt_enter_rad = 1e-5, tilt_leave_rad = 5e-6;
  /// Flags: the rim's contact point slid (its net displacement beyond rolling) further than
  /// slip_flag_rel * D ("sliding"); the
  /// lowest rim point higher than uplift_tol_m over the base while on the rim ("uplift": a
  /// bounce); deeper than penetration_flag_m below it ("penetration").
  double slip_flag_rel = 1e-3, uplift_tol_m = 1e-5, penetration_flag_m = 1e-4;
  /// Counted against the verdict above this fraction of the critical angle times D (the
  /// planar monitor's significant_critical_fraction).
  double significant_critical_fraction = 1e-3;
  /// Blow-up: a rate above this, rad/s.
  double blow_up_rate_radps = 1e3;
};

/// Watches a cylinder's run: rows of the cylinder's columns, its peaks, passes near upright
/// (local minima of the tilt below 1% of the critical angle: an engine cannot tell a landing
/// from a roll round the rim), the overturn (tilt reaching EngineInput::overturn_rad, its time
/// interpolated in the step, its azimuth), the rim's flags, and a state that is not finite.
class CylinderMonitor {
 public:
  explicit CylinderMonitor(const EngineInput& input, CylinderMonitorConfig config = {});
  void Start(const CylinderPose& pose);
  /// The pose after step n; false when the run must stop.
  bool Step(std::int64_t n, const CylinderPose& pose);
  void Finish();
  nlohmann::json Summary() const;
  RunOutcome Outcome() const;
  History TakeHistory() { return std::move(history_); }
  double last_t_s() const { return last_t_s_; }

 private:
  Sample Row(double t, const CylinderState& s) const;
  void Flag(int flag, double t, double size);

  const EngineInput& input_;
  const CylinderMonitorConfig config_;
  const CylinderBodyDef body_;
  const double alpha_rad_;
  History history_;
  CylinderState last_{};
  double last_t_s_ = 0.0;
  bool on_rim_ = false;
  std::int64_t steps_per_output_ = 1;
  RunStatus status_ = RunStatus::kCompleted;
  std::string status_detail_;
  double peak_tilt_rad_ = 0.0, peak_tilt_t_s_ = 0.0;
  double overturn_t_s_ = std::numeric_limits<double>::quiet_NaN(), overturn_azimuth_rad_ = 0.0;
  int passes_ = 0;
  double prev_tilt_rate_ = 0.0;
  double slip_m_ = 0.0, max_uplift_m_ = 0.0, max_penetration_m_ = 0.0;
  double slip_x_m_ = 0.0, slip_y_m_ = 0.0;  // the contact's net displacement, m
  // sliding, uplift, penetration, blow_up: first time raised (NaN: never), first significant.
  double flag_t_[4], significant_t_[4];
};

/// Runs `world` for input.steps steps (or until the monitor stops it), with summary.json's parts
/// every engine run writes, as RunEngineWorld's: "engine", "settings", "diagnostics" (for a world
/// that keeps them) and, for the kinematic drive, "kinematic".
template <CylinderWorld World>
EngineResult RunCylinderWorld(const std::string& engine, const EngineInput& input, World& world,
                              const CylinderMonitorConfig& config = {}) {
  const auto start = std::chrono::steady_clock::now();
  CylinderMonitor monitor(input, config);
  monitor.Start(world.ReadPose());
  for (std::int64_t n = 0; n < input.steps; ++n) {
    if ((n & 1023) == 0) ThrowIfStopRequested();
    world.ApplyDrive(n);
    world.Step();
    if (!monitor.Step(n + 1, world.ReadPose())) break;
  }
  monitor.Finish();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EngineResult r;
  r.summary = monitor.Summary();
  r.summary["engine"] = engine;
  r.summary["settings"] = world.Settings();
  r.summary["wall_s"] = wall_s;
  r.summary["real_time_factor"] = wall_s > 0.0 ? monitor.last_t_s() / wall_s : 0.0;
  if constexpr (requires { world.Diagnostics(); }) r.summary["diagnostics"] = world.Diagnostics();
  if (input.drive_kind == DriveKind::kKinematic) r.summary["kinematic"] = KinematicDriveJson(input);
  r.outcome = monitor.Outcome();
  r.wall_s = wall_s;
  r.history = monitor.TakeHistory();
  return r;
}

/// Builds World(input, settings) and runs it with RunCylinderWorld, as SimulateWorld does for
/// the planar worlds: a setting the world cannot take (std::invalid_argument) is a SceneError
/// naming `scene_path`.
template <CylinderWorld World, typename Settings>
EngineResult SimulateCylinderWorld(const std::string& engine, const std::string& scene_path,
                                   const EngineInput& input, const Settings& settings) {
  std::unique_ptr<World> world;
  try {
    world = std::make_unique<World>(input, settings);
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene_path + ": " + e.what());
  }
  return RunCylinderWorld(engine, input, *world);
}

}  // namespace rockbench
