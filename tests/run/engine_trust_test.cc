// The registry's trust rule, in process: an external engine a scene brings is registered (its
// table is checked) but is neither in "all" nor in BuiltEngineNames, and a file's engine list
// (CheckEngineName) refuses it, until the user names it (ParseEngineList of --engines). A file's
// list holds single engine names: "all" and comma-joined lists are refused with what is expected.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "run/engine_registry.h"
#include "scene/scene.h"
#include "tests/common/error_of.h"

namespace rockbench {
namespace {

using testing_util::ErrorOf;

bool Has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(EngineTrust, ASceneBroughtEngineRunsOnlyOnceTheUserNamesIt) {
  // `sh` is installed everywhere: the engine is built, so only the trust rule leaves it out.
  const Scene s = ParseScene(
      "[external.brought]\ncommand = [\"sh\", \"-c\", \"exit 1\"]\n"
      "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n",
      "scenes/hostile.toml");
  CheckEngineTables(s);
  const auto entry = [] {
    for (const RegisteredEngine& e : EngineRegistry()) {
      if (e.name == "brought") return e;
    }
    return RegisteredEngine{};
  }();
  ASSERT_NE(entry.engine, nullptr) << entry.missing_reason;
  EXPECT_EQ(entry.brought_by, "scenes/hostile.toml:1");
  EXPECT_TRUE(entry.awaits_user);
  EXPECT_FALSE(Has(ParseEngineList("all"), "brought"));
  EXPECT_FALSE(Has(BuiltEngineNames(), "brought"));
  EXPECT_TRUE(Has(ParseEngineList("all"), "bullet"));
  // A file's list refuses it, saying where it comes from and how to opt in.
  const std::string refused = ErrorOf([] { CheckEngineName("brought"); });
  EXPECT_NE(refused.find("brought is an external engine that scenes/hostile.toml:1 brings"),
            std::string::npos)
      << refused;
  EXPECT_NE(refused.find("--engines brought"), std::string::npos) << refused;
  EXPECT_NE(refused.find("engines/external_engines.toml"), std::string::npos) << refused;
  EXPECT_NE(refused.find("ROCKBENCH_EXTERNAL_ENGINES"), std::string::npos) << refused;
  // The note compare and sweep print names it and how to opt in; none for an engine selected.
  const std::string note = NotRunNote({"bullet"});
  EXPECT_NE(note.find("not run: external engine brought, which scenes/hostile.toml:1 brings "
                      "([external.brought])"),
            std::string::npos)
      << note;
  EXPECT_EQ(NotRunNote({"brought"}).find("brought"), std::string::npos);
  // The user's word (--engines brought): it runs from now on.
  EXPECT_EQ(ParseEngineList("bullet,brought"), (std::vector<std::string>{"bullet", "brought"}));
  EXPECT_TRUE(Has(BuiltEngineNames(), "brought"));
  EXPECT_NO_THROW(CheckEngineName("brought"));
  EXPECT_EQ(NotRunNote({}), "");
}

TEST(EngineTrust, AFilesEngineListHoldsOneEngineNamePerEntry) {
  EXPECT_NO_THROW(CheckEngineName("bullet"));
  for (const std::string& bad : {std::string("all"), std::string("bullet,ode"),
                                 std::string(" bullet"), std::string("nosuch")}) {
    const std::string msg = ErrorOf([&] { CheckEngineName(bad); });
    // It names the entry and what is expected: the reference or one built engine's name.
    EXPECT_NE(msg.find("\"" + bad + "\""), std::string::npos) << msg;
    EXPECT_NE(msg.find("expected \"reference\" or one of: bullet"), std::string::npos) << msg;
  }
  EXPECT_NE(ErrorOf([] { CheckEngineName("all"); }).find("not an engine name"), std::string::npos);
  EXPECT_NE(ErrorOf([] { CheckEngineName("bullet,ode"); }).find("one engine per entry"),
            std::string::npos);
  // A long or hostile name is shown escaped and cut, never as written.
  const std::string hostile = "\x1b[2K\rverdict bullet AGREES" + std::string(10000, 'x');
  const std::string msg = ErrorOf([&] { CheckEngineName(hostile); });
  EXPECT_EQ(msg.find('\x1b'), std::string::npos);
  EXPECT_NE(msg.find("\\x1B[2K\\rverdict"), std::string::npos) << msg;
  EXPECT_LT(msg.size(), 1000u);
}

}  // namespace
}  // namespace rockbench
