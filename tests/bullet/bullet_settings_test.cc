// Bullet's settings: the [bullet] table's checks (the shared engine input and the kinematic
// drive are tested on their own in tests/engines/drive_test.cc).
#include "engines/bullet/bullet_settings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "tests/common/one_block_scene.h"

namespace rockbench::bullet {
namespace {

TEST(EngineInputTest, RejectsImpossibleSettingsNamingTheKey) {
  // Each bad value is refused naming where it was set and the key (bullet.<key>), with what was
  // expected: the [bullet] table's schema for the settings, the step count for the time step.
  struct Case {
    const char* key;
    SettingValue value;
  };
  const Case cases[] = {
      {"time_step", 0.0},
      {"time_step", -1e-3},
      {"time_step", 1e-12},  // too many steps
      {"solver_iterations", std::int64_t{0}},
      {"solver_iterations", 2.5},
      {"erp", 1.5},
      {"erp2", -0.1},
      {"restitution", 2.0},
      {"friction", -1.0},
      {"rolling_friction", std::nan("")},
      {"restitution_velocity_threshold", -1.0},
      {"margin", -0.01},
      {"ground_depth", 0.0},
      {"kinematic_highpass_hz", -0.1},
      {"precision", std::string("half")},
      {"drive", std::string("pushed")},
      {"split_impulse", 1.0},
  };
  for (const Case& c : cases) {
    Scene s = testing_util::OneBlockScene();
    s.path = "scenes/x.toml";
    SetEngineSetting(s, "bullet", c.key, c.value);
    try {
      MakeBulletInput(s, GroundMotion());
      ADD_FAILURE() << "accepted a bad " << c.key;
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string("bullet.") + c.key + ":"), std::string::npos) << what;
      EXPECT_NE(what.find("scenes/x.toml"), std::string::npos) << what;
      EXPECT_NE(what.find("expected"), std::string::npos) << what;
    }
  }
  // An unknown key names the known ones.
  Scene s = testing_util::OneBlockScene();
  SetEngineSetting(s, "bullet", "time_stp", 1e-3);
  try {
    MakeBulletInput(s, GroundMotion());
    ADD_FAILURE() << "accepted bullet.time_stp";
  } catch (const SceneError& e) {
    EXPECT_NE(
        std::string(e.what()).find("bullet.time_stp: unknown key (expected one of: time_step"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rockbench::bullet
