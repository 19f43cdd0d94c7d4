// MuJoCo behind the engine interface (src/scene/engine.h): MujocoWorld stepped by the shared
// fixed-step loop, watched by the shared monitor; the cylinder, MujocoCylinderWorld, by the
// cylinder's run loop (engines/common/cylinder_world.h).
#include <mujoco/mujoco.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engines/common/cylinder_world.h"
#include "engines/common/fixed_step.h"
#include "engines/mujoco/mujoco_cylinder_world.h"
#include "engines/mujoco/mujoco_settings.h"
#include "engines/mujoco/mujoco_world.h"
#include "scene/body_kind.h"

namespace rockbench {
namespace mujoco {
namespace {

// Stiff contact (ours), and MuJoCo's own contact, friction and cone: what a user of its defaults
// gets.
TwoFamilyGrid Families() {
  return {"MuJoCo stiff contact",
          "MuJoCo defaults (soft contact)",
          {{"contact", std::string("mujoco_default")},
           {"friction", 1.0},
           {"cone", std::string("pyramidal")}},
          "stiff",
          "mujoco_default"};
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

  /// The planar block and the cylinder (mujoco_cylinder_world.h).
  std::vector<std::string> body_shapes() const override {
    return {PlanarBlockKind().shape, std::string(kCylinderShape)};
  }

  std::vector<SweepSetting> SweepGrid(bool quick) const override {
    return Families().StandardSweep(quick, 2e-3);
  }

  std::vector<SweepSetting> StressGrid() const override {
    // The CI subset: MuJoCo's own step (2e-3 s) in each family.
    return Families().Stress({2e-3, 1e-3, 1e-4, 1e-5}, [](double dt) { return dt == 2e-3; });
  }

  EngineResult Simulate(const Scene& scene, const GroundMotion& motion,
                        const SimulateOptions& options) const override {
    const MujocoRun run = MakeMujocoRun(scene, motion, options.stop_at_rest_after_s);
    EngineResult out = scene.three_dimensional()
                           ? SimulateCylinder(scene, run)
                           : SimulateWorld<MujocoWorld>("mujoco", scene, run.input, run.settings);
    char line[160];
    std::snprintf(line, sizeof line, "%s contact, %s, dt %.3g s",
                  std::string(ContactModelName(run.settings.contact)).c_str(),
                  DriveKindName(run.input.drive_kind), run.input.time_step_s);
    out.settings_line = line;
    return out;
  }

 private:
  // The cylinder, with the same settings and input; a setting the world cannot take is a
  // SceneError naming the scene file (as SimulateWorld's).
  static EngineResult SimulateCylinder(const Scene& scene, const MujocoRun& run) {
    return SimulateCylinderWorld<MujocoCylinderWorld>("mujoco", scene.path.string(), run.input,
                                                      run.settings);
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
