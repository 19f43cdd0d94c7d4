// MuJoCo behind the engine interface (engines/common/engine.h): MujocoWorld stepped by the shared
// fixed-step loop, watched by the shared monitor.
#include <mujoco/mujoco.h>

#include <cstdio>
#include <memory>

#include "engines/common/fixed_step.h"
#include "engines/mujoco/mujoco_settings.h"
#include "engines/mujoco/mujoco_world.h"

namespace rockbench {
namespace mujoco {
namespace {

constexpr const char* kStiffFamily = "MuJoCo stiff contact";
constexpr const char* kDefaultFamily = "MuJoCo defaults (soft contact)";

// A grid point of a family at step dt.
SweepSetting Point(bool mujoco_default, double dt_s) {
  SweepSetting s;
  s.family = mujoco_default ? kDefaultFamily : kStiffFamily;
  s.label = TimeStepLabel(dt_s);
  s.time_step_s = dt_s;
  s.settings = {{"time_step", dt_s}};
  // MuJoCo's own contact, friction and cone: what a user of its defaults gets.
  if (mujoco_default) {
    s.settings.emplace_back("contact", std::string("mujoco_default"));
    s.settings.emplace_back("friction", 1.0);
    s.settings.emplace_back("cone", std::string("pyramidal"));
  }
  return s;
}

class MujocoEngine final : public Engine {
 public:
  std::string name() const override { return "mujoco"; }

  std::string version() const override {
    char buf[64];
    std::snprintf(buf, sizeof buf, "MuJoCo %d.%d.%d", mj_version() / 100, mj_version() / 10 % 10,
                  mj_version() % 10);
    return buf;
  }

  const EngineSettingsSchema& settings_schema() const override { return MujocoSettingsSchema(); }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return TwoFamilyGrid{&Point}.StandardSweep(quick, 2e-3);
  }

  std::vector<SweepSetting> StressGrid() const override {
    // The CI subset: MuJoCo's own step (2e-3 s) in each family.
    return TwoFamilyGrid{&Point, "stiff", "mujoco_default"}.Stress(
        {2e-3, 1e-3, 1e-4, 1e-5}, [](double dt) { return dt == 2e-3; });
  }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const MujocoRun run = MakeMujocoRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = SimulateWorld<MujocoWorld>("mujoco", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "%s contact, %s, dt %.3g s",
                  std::string(ContactModelName(run.settings.contact)).c_str(),
                  DriveKindName(run.input.drive_kind), run.input.time_step_s);
    out.settings_line = line;
    return out;
  }
};

}  // namespace
}  // namespace mujoco

namespace engine_registry {
std::unique_ptr<Engine> Make_mujoco() {
  return std::make_unique<mujoco::MujocoEngine>();
}
}  // namespace engine_registry

}  // namespace rockbench
