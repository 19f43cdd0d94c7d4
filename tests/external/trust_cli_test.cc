// A scene (or a study) is data: an external engine it brings ([external.<name>]) runs only when
// the user names it on the command line or in a registry file they own. The hostile engine
// here creates a marker file when it runs: `compare` (engines "all"), `sweep` and a study that
// lists it leave no marker; `--engines NAME` and a registry file of the user's run it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"

namespace rockbench {
namespace {

using testing_util::Rockbench;
using testing_util::Shell;

class TrustCliTest : public testing_util::ScratchDirTest {
 protected:
  std::filesystem::path Marker() const { return dir_ / "marker"; }
  // The engine's table: a command that leaves the marker and fails (it never writes poses).
  std::string EngineTable() const {
    return "[external.evil]\ncommand = [\"sh\", \"-c\", \"touch '" + Marker().string() +
           "'; exit 1\"]\n";
  }
  // A block on a short pulse with the hostile engine's table.
  std::filesystem::path HostileScene() {
    return Write("evil.toml", EngineTable() +
                                  "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
                                  "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\n"
                                  "frequency_hz = 2.0\n[run]\nduration = 0.1\n");
  }
  std::string Out(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(TrustCliTest, CompareRunsASceneBroughtEngineOnlyWhenTheUserNamesIt) {
  const auto scene = HostileScene();
  // The default engines ("all"): the built-in and registered ones; the scene's is said not run.
  const auto all = Rockbench("compare " + scene.string() + " --quick --out " + Out("all"));
  EXPECT_EQ(all.exit_code, 0) << all.output;
  EXPECT_FALSE(std::filesystem::exists(Marker())) << all.output;
  EXPECT_NE(all.output.find("not run: external engine evil, which " + scene.string() +
                            ":1 brings ([external.evil])"),
            std::string::npos)
      << all.output;
  EXPECT_NE(all.output.find("--engines evil"), std::string::npos) << all.output;
  EXPECT_NE(all.output.find("ROCKBENCH_EXTERNAL_ENGINES"), std::string::npos) << all.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "all" / "evil")) << all.output;
  // Other engines named: still not run.
  const auto bullet =
      Rockbench("compare " + scene.string() + " --quick --engines bullet --out " + Out("bullet"));
  EXPECT_EQ(bullet.exit_code, 0) << bullet.output;
  EXPECT_FALSE(std::filesystem::exists(Marker())) << bullet.output;
  // Named on the command line: it runs (and fails, as it writes no poses).
  const auto named =
      Rockbench("compare " + scene.string() + " --quick --engines evil --out " + Out("named"));
  EXPECT_TRUE(std::filesystem::exists(Marker())) << named.output;
}

TEST_F(TrustCliTest, SweepOfAllEnginesLeavesASceneBroughtEngineOut) {
  const auto scene = HostileScene();
  const auto r = Rockbench("sweep " + scene.string() + " --quick --out " + Out("sweep"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(Marker())) << r.output;
  EXPECT_NE(r.output.find("not run: external engine evil"), std::string::npos) << r.output;
  EXPECT_EQ(testing_util::ReadFile(dir_ / "sweep" / "sweep.csv").find("evil"), std::string::npos);
}

TEST_F(TrustCliTest, AStudyListingASceneBroughtEngineIsRefusedUntilARegistryNamesIt) {
  HostileScene();
  const auto study = Write("study.toml",
                           "scene = \"evil.toml\"\nengines = [\"reference\", \"evil\"]\n"
                           "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [0.5]\n");
  const auto refused = Rockbench("ensemble " + study.string() + " --out " + Out("refused"));
  EXPECT_NE(refused.exit_code, 0) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(Marker())) << refused.output;
  // Refused at load: the study file, its line and key, where the scene brings the engine and
  // how to opt in.
  EXPECT_NE(refused.output.find(study.string() + ":2: engines: evil is an external engine that " +
                                (dir_ / "evil.toml").string() + ":1 brings"),
            std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("ROCKBENCH_EXTERNAL_ENGINES"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "refused" / "members.csv")) << refused.output;

  // The user's own registry (in another folder) names the same engine: the study runs it.
  std::filesystem::create_directories(dir_ / "mine");
  const auto registry = Write("mine/engines.toml", EngineTable());
  const auto run = Shell("ROCKBENCH_EXTERNAL_ENGINES=" + registry.string() + " " + ROCKBENCH_EXE +
                         " ensemble " + study.string() + " --out " + Out("registered"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(Marker())) << run.output;
  EXPECT_NE(testing_util::ReadFile(dir_ / "registered" / "members.csv").find(",evil,"),
            std::string::npos);
}

}  // namespace
}  // namespace rockbench
