#pragma once
/// The run loop every fixed-step engine shares: apply the base motion for step n, step, let the
/// monitor read the state, stop when it says so. What it needs of a world is FixedStepWorld.
#include <chrono>
#include <concepts>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "engine/engine.h"
#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "util/stop_request.h"

namespace rockbench {

/// What the run loop needs of an engine's world, the same for every fixed-step engine (each
/// world's header says only what its engine does in them):
/// - ApplyDrive(n): sets the base motion for step n, from t_n to t_{n+1};
/// - Step(): takes that one step;
/// - Read(n): the state after n steps (Read(0): the initial state), whose time is n dt;
/// - Settings(): the settings in use, summary.json's "settings";
/// - Diagnostics(), where the world keeps them: what the engine did of note, summary.json's
///   "diagnostics".
template <typename World>
concept FixedStepWorld = requires(World& world, const World& read_only, std::int64_t n) {
  world.ApplyDrive(n);
  world.Step();
  { read_only.Read(n) } -> std::same_as<StepReadout>;
  { read_only.Settings() } -> std::convertible_to<nlohmann::json>;
};

/// Runs `world` for input.steps steps (or until the monitor stops it) and returns the history,
/// the outcome and the monitor's summary with the wall time and the real-time factor.
template <FixedStepWorld World>
EngineResult RunFixedStepWorld(const EngineInput& input, World& world,
                               const MonitorConfig& monitor_config = {}) {
  const auto start = std::chrono::steady_clock::now();
  Monitor monitor(input, monitor_config);
  monitor.Start(world.Read(0));
  for (std::int64_t n = 0; n < input.steps; ++n) {
    // An embedding program's stop request (util/stop_request.h), every 1024 steps.
    if ((n & 1023) == 0) ThrowIfStopRequested();
    world.ApplyDrive(n);
    world.Step();
    if (!monitor.Step(n + 1, world.Read(n + 1))) break;
  }
  monitor.Finish();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EngineResult r;
  r.summary = monitor.Summary();
  r.summary["wall_s"] = wall_s;
  r.summary["real_time_factor"] = wall_s > 0.0 ? monitor.last().t_s / wall_s : 0.0;
  r.outcome = monitor.Outcome();
  r.wall_s = wall_s;
  r.history = monitor.TakeHistory();
  return r;
}

/// RunFixedStepWorld, with summary.json's parts every engine writes: "engine", "settings"
/// (World::Settings()), "diagnostics" (World::Diagnostics(), for a world that keeps them) and,
/// for the kinematic drive, "kinematic".
template <FixedStepWorld World>
EngineResult RunEngineWorld(const std::string& engine, const EngineInput& input, World& world) {
  EngineResult out = RunFixedStepWorld(input, world);
  out.summary["engine"] = engine;
  out.summary["settings"] = world.Settings();
  if constexpr (requires { world.Diagnostics(); }) out.summary["diagnostics"] = world.Diagnostics();
  if (input.drive_kind == DriveKind::kKinematic) {
    out.summary["kinematic"] = KinematicDriveJson(input);
  }
  return out;
}

/// Builds World(input, settings) and runs it with RunEngineWorld. A setting the world cannot
/// take (std::invalid_argument) is a SceneError naming the scene file.
template <FixedStepWorld World, typename Settings>
EngineResult SimulateWorld(const std::string& engine, const Scene& scene, const EngineInput& input,
                           const Settings& settings) {
  std::unique_ptr<World> world;
  try {
    world = std::make_unique<World>(input, settings);
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene.path.string() + ": " + e.what());
  }
  return RunEngineWorld(engine, input, *world);
}

}  // namespace rockbench
