// DART behind the engine interface (src/scene/engine.h): DartWorld stepped by the shared
// fixed-step loop, watched by the shared monitor.
#include <cstdio>
#include <dart/config.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engines/common/cylinder_world.h"
#include "engines/common/fixed_step.h"
#include "engines/dart/dart_cylinder_world.h"
#include "engines/dart/dart_settings.h"
#include "engines/dart/dart_world.h"
#include "scene/body_kind.h"

namespace rockbench {
namespace dart_engine {
namespace {

// Ours, and DART's own collision detector and friction. DART's contact ERP, allowance, cap and
// CFM are process-wide, so every point keeps ours (equal to DART's defaults): runs may share a
// process.
TwoFamilyGrid Families() {
  return {"DART (Dantzig + PGS)",
          "DART defaults (FCL friction 1)",
          {{"collision", std::string("fcl")}, {"friction", 1.0}}};
}

class DartEngine final : public Engine {
 public:
  std::string name() const override { return "dart"; }

  std::string version() const override { return std::string("DART ") + DART_VERSION; }

  const EngineSettingsSchema& settings_schema() const override { return DartSettingsSchema(); }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return Families().StandardSweep(quick, 5e-3);
  }

  std::vector<SweepSetting> StressGrid() const override { return Families().StandardStress(); }

  std::vector<std::string> body_shapes() const override {
    return {PlanarBlockKind().shape, std::string(kCylinderShape)};
  }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const DartRun run = MakeDartRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = scene.three_dimensional()
                           ? SimulateCylinder(scene, run)
                           : SimulateWorld<DartWorld>("dart", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "%s, %s, dt %.3g s",
                  DartLcpSolverName(run.settings.lcp_solver), DriveKindName(run.input.drive_kind),
                  run.input.time_step_s);
    out.settings_line = line;
    return out;
  }

 private:
  // The cylinder (scene.three_dimensional()): DartCylinderWorld run by the shared cylinder
  // loop, with the summary's parts every DART run writes (diagnostics; kinematic).
  static EngineResult SimulateCylinder(const Scene& scene, const DartRun& run) {
    return SimulateCylinderWorld<DartCylinderWorld>("dart", scene.path.string(), run.input,
                                                    run.settings);
  }
};

}  // namespace
}  // namespace dart_engine

namespace engine_registry {
std::unique_ptr<Engine> Make_dart() {
  return std::make_unique<dart_engine::DartEngine>();
}
}  // namespace engine_registry

}  // namespace rockbench
