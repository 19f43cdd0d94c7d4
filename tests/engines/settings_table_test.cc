// An engine's settings table written once (SettingsTable, scene/engine_settings.h): each key of
// the schema is bound to the member of the engine's settings struct it sets. Checked on a
// made-up struct (defaults, every kind of key, unbound keys, the schema's messages), and on every
// built-in engine of the build: each of its keys, set to a value other than the default, changes
// the struct MakeEngineRun reads, and no key leaves it at its default.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error_of.h"
#include "engines/common/engine_input.h"
#include "motion/ground_motion.h"
#include "scene/engine_settings.h"
#include "scene/scene.h"
#if ROCKBENCH_HAVE_BOX2D
#include "engines/box2d/box2d_settings.h"
#endif
#include "engines/bullet/bullet_settings.h"
#if ROCKBENCH_HAVE_DART
#include "engines/dart/dart_settings.h"
#endif
#if ROCKBENCH_HAVE_MUJOCO
#include "engines/mujoco/mujoco_settings.h"
#endif
#if ROCKBENCH_HAVE_ODE
#include "engines/ode/ode_settings.h"
#endif
#if ROCKBENCH_HAVE_SICONOS
#include "engines/siconos/siconos_settings.h"
#endif

namespace rockbench {
namespace {

// A single block at rest, 0.1 s: enough for MakeEngineRun to sample a base motion.
Scene OneBlock() {
  return ParseScene(
      "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2500.0\n"
      "[run]\nduration = 0.1\noutput_interval = 0.01\n",
      "one_block.toml");
}

enum class Shape { kBox, kDrum };
const char* ShapeName(Shape s) {
  return s == Shape::kDrum ? "drum" : "box";
}

// A made-up engine's settings.
struct Made {
  double stiffness = 2.5;
  int passes = 3;
  bool fast = true;
  Shape shape = Shape::kDrum;
  bool operator==(const Made&) const = default;
};

SettingsTable<Made> MadeTable() {
  SettingsTable<Made> t("made");
  AddTimeStepSetting(t.unbound(), "-", "step");
  t.Number("stiffness", &Made::stiffness, SettingRange::kPositive, "N/m", "-", "k");
  t.Integer("passes", &Made::passes, 1, 9, "-", "n");
  t.Flag("fast", &Made::fast, "-", "f");
  t.Choice("shape", &Made::shape, {Shape::kBox, Shape::kDrum}, ShapeName, "-", "s");
  return t;
}

TEST(SettingsTable, DefaultsAreTheStructsAndReadBack) {
  const SettingsTable<Made> t = MadeTable();
  const EngineSettingsSchema& schema = t.schema();
  ASSERT_EQ(schema.settings.size(), 5u);
  EXPECT_EQ(std::get<double>(schema.Find("stiffness")->default_value), 2.5);
  EXPECT_EQ(std::get<std::int64_t>(schema.Find("passes")->default_value), 3);
  EXPECT_EQ(std::get<bool>(schema.Find("fast")->default_value), true);
  EXPECT_EQ(std::get<std::string>(schema.Find("shape")->default_value), "drum");
  EXPECT_EQ(schema.Find("shape")->choices, (std::vector<std::string>{"box", "drum"}));
  EXPECT_EQ(t.Read(ResolveEngineSettings(OneBlock(), schema)), Made{});

  Scene s = OneBlock();
  SetEngineSetting(s, "made", "stiffness", 7.0);
  SetEngineSetting(s, "made", "passes", std::int64_t{9});
  SetEngineSetting(s, "made", "fast", false);
  SetEngineSetting(s, "made", "shape", std::string("box"));
  SetEngineSetting(s, "made", "time_step", 2e-4);  // unbound: read by MakeEngineInput only
  const Made m = t.Read(ResolveEngineSettings(s, schema));
  EXPECT_EQ(m.stiffness, 7.0);
  EXPECT_EQ(m.passes, 9);
  EXPECT_FALSE(m.fast);
  EXPECT_EQ(m.shape, Shape::kBox);
}

TEST(SettingsTable, MessagesAreTheSchemas) {
  Scene s = OneBlock();
  SetEngineSetting(s, "made", "shape", std::string("cone"));
  const std::string msg =
      testing_util::ErrorOf([&] { ResolveEngineSettings(s, MadeTable().schema()); });
  EXPECT_NE(msg.find("made.shape: expected \"box\" or \"drum\", got \"cone\""), std::string::npos)
      << msg;
  // A table resolved against another schema is a programming error, not a wrong read.
  EngineSettingsSchema other;
  other.engine = "made";
  EXPECT_THROW(MadeTable().Read(ResolveEngineSettings(OneBlock(), other)), std::logic_error);
}

// A valid value of `d` other than its default, or nothing when it has no other (a choice of
// one).
std::optional<SettingValue> OtherValue(const SettingDef& d) {
  if (const double* v = std::get_if<double>(&d.default_value)) {
    // Twice, half, or 0.5 from 0 or infinity: one of them is inside every range and bound the
    // engines use.
    for (const double c : {std::isfinite(*v) && *v != 0.0 ? 2.0 * *v : 0.5, *v / 2.0, 0.75}) {
      Scene s = OneBlock();
      EngineSettingsSchema one;
      one.engine = "x";
      one.settings.push_back(d);
      SetEngineSetting(s, "x", d.key, c);
      try {
        ResolveEngineSettings(s, one);
        if (c != *v) return c;
      } catch (const SceneError&) {
      }
    }
    return std::nullopt;
  }
  if (const std::int64_t* i = std::get_if<std::int64_t>(&d.default_value)) {
    return *i < d.max_integer ? *i + 1 : *i - 1;
  }
  if (const bool* b = std::get_if<bool>(&d.default_value)) return !*b;
  const std::string& c = std::get<std::string>(d.default_value);
  for (const std::string& other : d.choices) {
    if (other != c) return other;
  }
  return std::nullopt;
}

// The keys MakeEngineInput reads (EngineInput, not the engine's struct).
bool Unbound(const std::string& key) {
  return key == "time_step" || key == "drive" || key == "kinematic_highpass_hz";
}

// Each bound key of `schema`, set alone to another value, changes what `read` gives.
template <class S>
void EachKeyReachesItsMember(const EngineSettingsSchema& schema,
                             const std::function<S(const Scene&)>& read) {
  EXPECT_EQ(read(OneBlock()), S{}) << schema.engine << ": the defaults are the struct's";
  int bound = 0;
  for (const SettingDef& d : schema.settings) {
    if (Unbound(d.key)) continue;
    const std::optional<SettingValue> v = OtherValue(d);
    ASSERT_TRUE(v.has_value()) << schema.engine << "." << d.key;
    Scene s = OneBlock();
    SetEngineSetting(s, schema.engine, d.key, *v);
    if (schema.engine == "ode" && d.key == "friction_pyramid") {
      SetEngineSetting(s, "ode", "friction", 1.0);  // the pyramid needs a finite friction
      Scene f = OneBlock();
      SetEngineSetting(f, "ode", "friction", 1.0);
      EXPECT_NE(read(s), read(f)) << "ode.friction_pyramid";
      ++bound;
      continue;
    }
    EXPECT_NE(read(s), S{}) << schema.engine << "." << d.key << " = " << SettingText(*v)
                            << " does not reach the engine's settings";
    ++bound;
  }
  EXPECT_GT(bound, 3) << schema.engine;
}

TEST(SettingsTable, EveryBulletKeyReachesItsMember) {
  EachKeyReachesItsMember<bullet::BulletConfig>(bullet::BulletSettingsSchema(), [](const Scene& s) {
    return bullet::MakeBulletInput(s, GroundMotion()).config;
  });
}

#if ROCKBENCH_HAVE_BOX2D
TEST(SettingsTable, EveryBox2dKeyReachesItsMember) {
  using namespace box2d_engine;
  EachKeyReachesItsMember<Box2dSettings>(Box2dSettingsSchema(), [](const Scene& s) {
    return MakeBox2dRun(s, GroundMotion(), std::numeric_limits<double>::infinity()).settings;
  });
}
#endif

#if ROCKBENCH_HAVE_DART
TEST(SettingsTable, EveryDartKeyReachesItsMember) {
  using namespace dart_engine;
  EachKeyReachesItsMember<DartSettings>(DartSettingsSchema(), [](const Scene& s) {
    return MakeDartRun(s, GroundMotion(), std::numeric_limits<double>::infinity()).settings;
  });
}
#endif

#if ROCKBENCH_HAVE_MUJOCO
TEST(SettingsTable, EveryMujocoKeyReachesItsMember) {
  using namespace mujoco;
  EachKeyReachesItsMember<MujocoSettings>(MujocoSettingsSchema(), [](const Scene& s) {
    return MakeMujocoRun(s, GroundMotion(), std::numeric_limits<double>::infinity()).settings;
  });
}
#endif

#if ROCKBENCH_HAVE_ODE
TEST(SettingsTable, EveryOdeKeyReachesItsMember) {
  using namespace ode;
  EachKeyReachesItsMember<OdeSettings>(OdeSettingsSchema(), [](const Scene& s) {
    return MakeOdeRun(s, GroundMotion(), std::numeric_limits<double>::infinity()).settings;
  });
}
#endif

#if ROCKBENCH_HAVE_SICONOS
TEST(SettingsTable, EverySiconosKeyReachesItsMember) {
  using namespace siconos_engine;
  EachKeyReachesItsMember<SiconosSettings>(SiconosSettingsSchema(), [](const Scene& s) {
    return MakeSiconosRun(s, GroundMotion(), std::numeric_limits<double>::infinity()).settings;
  });
}
#endif

}  // namespace
}  // namespace rockbench
