// DART behind the engine interface (engines/common/engine.h): DartWorld stepped by the shared
// fixed-step loop, watched by the shared monitor.
#include <cstdio>
#include <dart/config.hpp>
#include <memory>

#include "engines/common/fixed_step.h"
#include "engines/dart/dart_settings.h"
#include "engines/dart/dart_world.h"

namespace rockbench {
namespace dart_engine {
namespace {

constexpr const char* kOurs = "DART (Dantzig + PGS)";
constexpr const char* kDefaults = "DART defaults (FCL friction 1)";

// A grid point of a family at step dt. DART's contact ERP, allowance, cap and CFM are
// process-wide, so every point keeps ours (equal to DART's defaults): runs may share a process.
SweepSetting Point(bool dart_default, double dt_s) {
  SweepSetting s;
  s.family = dart_default ? kDefaults : kOurs;
  s.label = TimeStepLabel(dt_s);
  s.time_step_s = dt_s;
  s.settings = {{"time_step", dt_s}};
  if (dart_default) {
    s.settings.emplace_back("collision", std::string("fcl"));
    s.settings.emplace_back("friction", 1.0);
  }
  return s;
}

class DartEngine final : public Engine {
 public:
  std::string name() const override { return "dart"; }

  std::string version() const override { return std::string("DART ") + DART_VERSION; }

  const EngineSettingsSchema& settings_schema() const override { return DartSettingsSchema(); }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return TwoFamilyGrid{&Point}.StandardSweep(quick, 5e-3);
  }

  std::vector<SweepSetting> StressGrid() const override {
    return TwoFamilyGrid{&Point}.StandardStress();
  }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const DartRun run = MakeDartRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = SimulateWorld<DartWorld>("dart", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "%s, %s, dt %.3g s",
                  DartLcpSolverName(run.settings.lcp_solver), DriveKindName(run.input.drive_kind),
                  run.input.time_step_s);
    out.settings_line = line;
    return out;
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
