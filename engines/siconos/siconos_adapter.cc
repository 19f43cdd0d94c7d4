// Siconos behind the engine interface (src/scene/engine.h): SiconosWorld stepped by the
// shared fixed-step loop, watched by the shared monitor.
#include <cstdio>
#include <memory>

#include "engines/common/fixed_step.h"
#include "engines/siconos/siconos_cylinder_world.h"
#include "engines/siconos/siconos_settings.h"
#include "engines/siconos/siconos_system.h"
#include "engines/siconos/siconos_world.h"
#include "scene/body_kind.h"

namespace rockbench {
namespace siconos_engine {
namespace {

// Ours (NSGS to 1e-8, Lemke fallback), and NSGS at the numerics' own tolerance and cap (1e-4,
// 1000) without a fallback.
TwoFamilyGrid Families() {
  return {"Siconos Moreau-Jean (NSGS 1e-8)",
          "Siconos defaults (NSGS 1e-4)",
          {{"solver_tolerance", 1e-4},
           {"lemke_fallback", false},
           {"solver_max_iterations", std::int64_t{1000}}}};
}

class SiconosEngine final : public Engine {
 public:
  std::string name() const override { return "siconos"; }

  std::string version() const override { return SiconosVersionString(); }

  const EngineSettingsSchema& settings_schema() const override { return SiconosSettingsSchema(); }

  /// The planar block and the cylinder (siconos_cylinder_world.h).
  std::vector<std::string> body_shapes() const override {
    return {PlanarBlockKind().shape, std::string(kCylinderShape)};
  }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return Families().StandardSweep(quick, 5e-3);
  }

  std::vector<SweepSetting> StressGrid() const override { return Families().StandardStress(); }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const SiconosRun run = MakeSiconosRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = scene.three_dimensional()
                           ? SimulateCylinder(scene.path.string(), run.input, run.settings)
                           : SimulateWorld<SiconosWorld>("siconos", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "Moreau-Jean theta %.3g, %s, %s, dt %.3g s",
                  run.settings.theta, SiconosSolverName(run.settings.solver),
                  DriveKindName(run.input.drive_kind), run.input.time_step_s);
    out.settings_line = line;
    return out;
  }
};

}  // namespace
}  // namespace siconos_engine

namespace engine_registry {
std::unique_ptr<Engine> Make_siconos() {
  return std::make_unique<siconos_engine::SiconosEngine>();
}
}  // namespace engine_registry

}  // namespace rockbench
