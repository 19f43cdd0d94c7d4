// A study's `engines` list is checked when the study is loaded, not row by row: each entry is
// "reference" or one engine of the build or of a registry file the user owns. "all", a
// comma-joined list, a name with spaces, an unknown name and an engine the study's scene brings
// ([external.<name>]) are refused with the study file, the line, the key and what is expected.
#include <gtest/gtest.h>

#include <string>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "common/sine_pulse_block.h"
#include "scene/scene.h"
#include "study/study.h"

namespace rockbench {
namespace {

class StudyEngineListTest : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    Write("block.toml", testing_util::SinePulseBlockToml("0.2"));
  }
  // The message LoadStudy throws for a study of these engines (the list on line 2).
  std::string Error(const std::string& engines, const std::string& scene = "block.toml") {
    try {
      LoadStudy(Write("study.toml", "scene = \"" + scene + "\"\nengines = " + engines + "\n"));
    } catch (const SceneError& e) {
      return e.what();
    }
    return "no error";
  }
  std::string Where() const { return (dir_ / "study.toml").string() + ":2: engines: "; }
};

TEST_F(StudyEngineListTest, OneEngineNamePerEntryRefusedAtLoadWithWhatIsExpected) {
  const std::string all = Error("[\"reference\", \"all\"]");
  EXPECT_NE(all.find(Where() + "\"all\" is not an engine name"), std::string::npos) << all;
  EXPECT_NE(all.find("expected \"reference\" or one of: bullet"), std::string::npos) << all;
  const std::string joined = Error("[\"bullet,ode\"]");
  EXPECT_NE(joined.find(Where() + "\"bullet,ode\" is not an engine name: one engine per entry"),
            std::string::npos)
      << joined;
  const std::string spaced = Error("[\" bullet\"]");
  EXPECT_NE(spaced.find(Where() + "unknown engine \" bullet\""), std::string::npos) << spaced;
  const std::string unknown = Error("[\"reference\", \"nosuch\"]");
  EXPECT_NE(unknown.find(Where() + "unknown engine \"nosuch\""), std::string::npos) << unknown;
  EXPECT_EQ(Error("[\"reference\", \"bullet\"]"), "no error");
}

TEST_F(StudyEngineListTest, AnEngineTheSceneBringsIsRefusedWithHowToOptIn) {
  Write("brings.toml", "[external.brought]\ncommand = [\"sh\", \"-c\", \"exit 1\"]\n" +
                           testing_util::ReadFile(dir_ / "block.toml"));
  const std::string msg = Error("[\"reference\", \"brought\"]", "brings.toml");
  EXPECT_NE(msg.find(Where() + "brought is an external engine that " +
                     (dir_ / "brings.toml").string() + ":1 brings ([external.brought])"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("ROCKBENCH_EXTERNAL_ENGINES"), std::string::npos) << msg;
}

}  // namespace
}  // namespace rockbench
