// ODE behind the engine interface (src/scene/engine.h): OdeWorld stepped by the shared
// fixed-step loop, watched by the shared monitor; the cylinder (a 3-D scene) in
// OdeCylinderWorld, run by the shared cylinder loop.
#include <ode/ode.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "engines/common/cylinder_world.h"
#include "engines/common/fixed_step.h"
#include "engines/ode/ode_cylinder_world.h"
#include "engines/ode/ode_settings.h"
#include "engines/ode/ode_world.h"

namespace rockbench {
namespace ode {
namespace {

// Ours (dWorldStep), and ODE's own contact handling: QuickStep with its 20 iterations, no cap
// on the push-out.
TwoFamilyGrid Families() {
  return {"ODE world_step",
          "ODE defaults (quick_step 20 it)",
          {{"stepper", std::string("quick_step")},
           {"quick_step_iterations", std::int64_t{20}},
           {"contact_max_correcting_vel", std::numeric_limits<double>::infinity()}},
          "world_step",
          "defaults"};
}

class OdeEngine final : public Engine {
 public:
  std::string name() const override { return "ode"; }

  std::string version() const override {
    return std::string("ODE ") + dODE_VERSION + " (double, " +
           (dCheckConfiguration("ODE_double_precision") ? "checked" : "unchecked") + ")";
  }

  const EngineSettingsSchema& settings_schema() const override { return OdeSettingsSchema(); }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return Families().Sweep(
        quick ? std::vector<double>{1e-3, 1e-4}
              : std::vector<double>{1.0 / 60.0, 5e-3, 1e-3, 5e-4, 1e-4, 5e-5, 1e-5});
  }

  std::vector<SweepSetting> StressGrid() const override { return Families().StandardStress(); }

  std::vector<std::string> body_shapes() const override { return {"block", "cylinder"}; }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const OdeRun run = MakeOdeRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = scene.three_dimensional()
                           ? SimulateCylinder(scene, run)
                           : SimulateWorld<OdeWorld>("ode", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "%s, %s, dt %.3g s", OdeStepperName(run.settings.stepper),
                  DriveKindName(run.input.drive_kind), run.input.time_step_s);
    out.settings_line = line;
    return out;
  }

 private:
  // The cylinder's run (the same settings and input as the blocks'). A setting the world cannot
  // take is a SceneError naming the scene file, as SimulateWorld's.
  static EngineResult SimulateCylinder(const Scene& scene, const OdeRun& run) {
    return SimulateCylinderWorld<OdeCylinderWorld>("ode", scene.path.string(), run.input,
                                                   run.settings);
  }
};

}  // namespace
}  // namespace ode

namespace engine_registry {
std::unique_ptr<Engine> Make_ode() {
  return std::make_unique<ode::OdeEngine>();
}
}  // namespace engine_registry

}  // namespace rockbench
