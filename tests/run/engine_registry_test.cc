// The engine registry: the list engines/CMakeLists.txt generates, --engines lists, and the check
// of a scene's non-scene tables against the engines of the build.
#include "run/engine_registry.h"

#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "tests/common/error_of.h"

namespace rockbench {
namespace {

const std::string kBlock = "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n";

using testing_util::ErrorOf;

TEST(EngineRegistry, ListsEveryRegisteredEngineOnceBuiltOrNot) {
  std::set<std::string> names;
  for (const RegisteredEngine& e : EngineRegistry()) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name;
    // Built, or left out with a reason: never silently neither.
    EXPECT_TRUE((e.engine != nullptr) != !e.missing_reason.empty()) << e.name;
    if (e.engine != nullptr) {
      EXPECT_EQ(e.engine->name(), e.name);
    }
    EXPECT_NE(EngineListText().find(e.name + ": "), std::string::npos) << e.name;
  }
  // Bullet is a required dependency (cmake/Dependencies.cmake).
  EXPECT_NE(FindEngine("bullet"), nullptr);
  // The reference is an engine behind the same interface, found by name, and not a built
  // physics engine.
  ASSERT_NE(FindEngine("reference"), nullptr);
  EXPECT_EQ(FindEngine("reference")->name(), "reference");
  EXPECT_TRUE(IsReference(FindEngine("reference")->name()));
  for (const std::string& n : BuiltEngineNames()) EXPECT_FALSE(IsReference(n)) << n;
  EXPECT_EQ(FindEngine("bulet"), nullptr);
}

TEST(EngineRegistry, EnginesListsAreAllOrNamesOfBuiltEngines) {
  EXPECT_EQ(ParseEngineList("all"), BuiltEngineNames());
  EXPECT_EQ(ParseEngineList("bullet"), std::vector<std::string>{"bullet"});
  const std::string msg = ErrorOf([] { ParseEngineList("bullet,bulet"); });
  EXPECT_NE(msg.find("bulet"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bullet"), std::string::npos) << msg << " (should name the built ones)";
  for (const RegisteredEngine& e : EngineRegistry()) {
    if (e.engine == nullptr) {
      const std::string left_out = ErrorOf([&] { ParseEngineList(e.name); });
      EXPECT_NE(left_out.find(e.missing_reason), std::string::npos) << left_out;
    }
  }
}

TEST(EngineRegistry, ATableThatIsNeitherTheScenesNorAnEnginesIsAnError) {
  const Scene s = ParseScene(kBlock + "\n[blok3]\nwidth = 1\n", "scenes/x.toml");
  const std::string msg = ErrorOf([&] { CheckEngineTables(s); });
  EXPECT_NE(msg.find("scenes/x.toml:6: [blok3]: unknown table"), std::string::npos) << msg;
  EXPECT_NE(msg.find("block1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bullet"), std::string::npos) << msg;
  // The same through an override.
  const Scene o = ParseScene(kBlock, "scenes/x.toml", {"nosuch.key=1"});
  EXPECT_NE(ErrorOf([&] { CheckEngineTables(o); }).find("[nosuch]: unknown table"),
            std::string::npos);
  // An engine's table is checked against its schema.
  const Scene b = ParseScene(kBlock + "[bullet]\ntime_step = 1e-3\n", "scenes/x.toml");
  EXPECT_NO_THROW(CheckEngineTables(b));
}

}  // namespace
}  // namespace rockbench
