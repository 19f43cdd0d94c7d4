// External engines from the command line: `rockbench engines` lists them (or says why one is
// left out), `compare` runs one a scene names, and in a study a hanging engine is a row, never
// the end of the study.
#include <gtest/gtest.h>

#include <string>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"

namespace rockbench {
namespace {

using testing_util::ReadFile;
using testing_util::Rockbench;

const std::string kSource = ROCKBENCH_SOURCE_DIR;

class ExternalCliTest : public testing_util::ScratchDirTest {};

TEST_F(ExternalCliTest, ComparesThePythonExampleWithTheReference) {
  const auto r = Rockbench("compare " + kSource +
                           "/examples/python_housner/housner_python.toml --engines housner_py "
                           "--quick --out " +
                           (dir_ / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("housner_py impacts faster than 0.02 rad/s: 4 of 4 matched"),
            std::string::npos)
      << r.output;
  const std::string summary = ReadFile(dir_ / "out" / "summary.json");
  EXPECT_NE(summary.find("\"process_wall_s\""), std::string::npos);
}

TEST_F(ExternalCliTest, AnEngineListsItselfOrSaysWhyItIsLeftOut) {
  Write("registry.toml", "[external.ghost]\ncommand = [\"no-such-program-rockbench\"]\n");
  const auto r =
      testing_util::Shell("ROCKBENCH_EXTERNAL_ENGINES=" + (dir_ / "registry.toml").string() + " " +
                          ROCKBENCH_EXE + " engines");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("ghost: left out of this build (its program "
                          "'no-such-program-rockbench' is not installed)"),
            std::string::npos)
      << r.output;
  // A registry that cannot be read says so and leaves the rest working.
  Write("bad.toml", "[external.x]\ncolour = 1\n");
  const auto b = testing_util::Shell("ROCKBENCH_EXTERNAL_ENGINES=" + (dir_ / "bad.toml").string() +
                                     " " + ROCKBENCH_EXE + " engines");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_NE(b.output.find(":2: external.x.colour: unknown key (expected manifest or command)"),
            std::string::npos)
      << b.output;
}

TEST_F(ExternalCliTest, AHangInAStudyIsARow) {
  Write("block.toml", "[external.hangs]\ncommand = [\"python3\", \"" + kSource +
                          "/tests/external/faulty_engine.py\", \"hang\"]\n"
                          "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
                          "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\n"
                          "frequency_hz = 2.0\n[run]\nduration = 0.5\n"
                          "[hangs]\ntime_step = 1e-3\nwall_limit_s = 1\n");
  const auto study = Write("study.toml",
                           "scene = \"block.toml\"\nengines = [\"reference\", \"hangs\"]\n"
                           "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [0.5, 3]\n");
  // A study runs a scene's engine that a registry file of the user's names (trust_cli_test.cc).
  const auto registry =
      Write("registry.toml", "[external.hangs]\ncommand = [\"python3\", \"" + kSource +
                                 "/tests/external/faulty_engine.py\", \"hang\"]\n");
  const auto r = testing_util::Shell("ROCKBENCH_EXTERNAL_ENGINES=" + registry.string() + " " +
                                     ROCKBENCH_EXE + " ensemble " + study.string() + " --out " +
                                     (dir_ / "out").string() + " --jobs 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string members = ReadFile(dir_ / "out" / "members.csv");
  int hung = 0;
  for (size_t p = members.find("killed after its wall-clock limit of 1 s"); p != std::string::npos;
       p = members.find("killed after its wall-clock limit of 1 s", p + 1)) {
    ++hung;
  }
  EXPECT_EQ(hung, 2) << members;
  EXPECT_NE(members.find(",reference,"), std::string::npos) << members;
}

}  // namespace
}  // namespace rockbench
