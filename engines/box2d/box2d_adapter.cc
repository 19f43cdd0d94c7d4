// Box2D behind the engine interface (src/scene/engine.h): Box2dWorld stepped by the shared
// fixed-step loop, watched by the shared monitor.
#include <box2d/box2d.h>

#include <cstdio>
#include <memory>

#include "engines/box2d/box2d_settings.h"
#include "engines/box2d/box2d_world.h"
#include "engines/common/fixed_step.h"

namespace rockbench {
namespace box2d_engine {
namespace {

// Ours (lengths scaled), and Box2D's own: no scaling (its 1 cm skin on the blocks as they are),
// the testbed's 8 velocity and 3 position iterations, b2FixtureDef's friction 0.2.
TwoFamilyGrid Families() {
  return {"Box2D scaled lengths",
          "Box2D defaults (unscaled 8/3 it friction 0.2)",
          {{"length_scale", 1.0},
           {"velocity_iterations", std::int64_t{8}},
           {"position_iterations", std::int64_t{3}},
           {"friction", 0.2}}};
}

class Box2dEngine final : public Engine {
 public:
  std::string name() const override { return "box2d"; }

  std::string version() const override {
    char text[64];
    std::snprintf(text, sizeof text, "Box2D %d.%d.%d (float)", b2_version.major, b2_version.minor,
                  b2_version.revision);
    return text;
  }

  const EngineSettingsSchema& settings_schema() const override { return Box2dSettingsSchema(); }

  // The coarsest step is Box2D's own, 1/60 s.
  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return Families().StandardSweep(quick, 1.0 / 60.0);
  }

  std::vector<SweepSetting> StressGrid() const override { return Families().StandardStress(); }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const Box2dRun run = MakeBox2dRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = SimulateWorld<Box2dWorld>("box2d", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "float, length_scale %g, %d/%d it, %s, dt %.3g s",
                  run.settings.length_scale, run.settings.velocity_iterations,
                  run.settings.position_iterations, DriveKindName(run.input.drive_kind),
                  run.input.time_step_s);
    out.settings_line = line;
    return out;
  }
};

}  // namespace
}  // namespace box2d_engine

namespace engine_registry {
std::unique_ptr<Engine> Make_box2d() {
  return std::make_unique<box2d_engine::Box2dEngine>();
}
}  // namespace engine_registry

}  // namespace rockbench
