// What `compare` leaves when an engine fails or the command is stopped (issue 38): a failing
// engine among good ones is its own verdict and the others' outputs are written (exit 4); a
// compare into an old folder says what it wrote, and render draws that only; SIGTERM ends the
// engine and the helper it started in a session of its own, removes the engine's run folder,
// and leaves a user's files named like temporaries alone.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "common/spawn_quiet.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;
using testing_util::ReadFile;
using testing_util::Rockbench;

const std::string kFaulty = std::string(ROCKBENCH_SOURCE_DIR) + "/tests/external/faulty_engine.py";

// A block at rest under a small pulse (0.1 g, below its uplift at g / 3), 0.5 s, and the
// external engines `engines` (name -> faulty_engine.py mode, or a whole command line).
std::string Scene(const std::vector<std::pair<std::string, std::string>>& engines) {
  std::string s;
  for (const auto& [name, command] : engines) {
    s += "[external." + name + "]\ncommand = " + command + "\n";
  }
  s += "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
       "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.1\nfrequency_hz = 2.0\n"
       "[run]\nduration = 0.5\n";
  for (const auto& e : engines) s += "[" + e.first + "]\ntime_step = 1e-3\n";
  return s;
}

std::string Faulty(const std::string& mode) {
  return "[\"python3\", \"" + kFaulty + "\", \"" + mode + "\"]";
}

class FailingEngineTest : public testing_util::ScratchDirTest {};

// good, bad (exits 3), good2: both good engines are compared and written; bad is a verdict line
// and an entry of comparison.json and summary.json; the command exits 4.
TEST_F(FailingEngineTest, AFailingEngineIsItsOwnVerdictAndTheOthersAreWritten) {
  const auto scene =
      Write("scene.toml",
            Scene({{"good", Faulty("good")}, {"bad", Faulty("exit")}, {"good2", Faulty("good")}}));
  const fs::path out = dir_ / "out";
  const auto r = Rockbench("compare " + scene.string() +
                           " --engines good,bad,good2 --quick --out " + out.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("verdict good: AGREES"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("verdict good2: AGREES"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("verdict bad: FAILED: its command"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("exit code 3; its last words:   | faulty engine: cannot simulate this on "
                          "purpose"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("outputs in " + out.string() +
                          " (comparison.json, comparison.csv, summary.json, reference/, good/, "
                          "good2/)"),
            std::string::npos)
      << r.output;
  for (const char* f : {"good/history.csv", "good2/history.csv", "reference/history.csv",
                        "comparison.json", "comparison.csv", "summary.json"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  EXPECT_FALSE(fs::exists(out / "bad"));
  const std::string summary = ReadFile(out / "summary.json");
  EXPECT_NE(summary.find("\"failed_engines\": {\n    \"bad\": \"its command"), std::string::npos)
      << summary;
  const std::string comparison = ReadFile(out / "comparison.json");
  EXPECT_NE(comparison.find("\"engine\": \"bad\""), std::string::npos) << comparison;
  const std::string csv = ReadFile(out / "comparison.csv");
  EXPECT_NE(csv.find("\ngood,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\ngood2,"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("\nbad,"), std::string::npos) << csv;
}

// A compare into a folder an earlier compare with more engines wrote: summary.json lists what
// this one wrote, and render leaves the older engine folder out, saying so.
TEST_F(FailingEngineTest, RenderDrawsOnlyWhatTheLastCompareWrote) {
  const auto scene =
      Write("scene.toml", Scene({{"good", Faulty("good")}, {"older", Faulty("good")}}));
  const fs::path out = dir_ / "out";
  const auto first = Rockbench("compare " + scene.string() +
                               " --engines good,older --quick --out " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto second =
      Rockbench("compare " + scene.string() + " --engines good --quick --out " + out.string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  // The older folder stays (it is not this command's to delete) but is not listed.
  EXPECT_TRUE(fs::exists(out / "older" / "history.csv"));
  const std::string summary = ReadFile(out / "summary.json");
  EXPECT_NE(summary.find("\"engines_written\": [\n    \"reference\",\n    \"good\"\n  ]"),
            std::string::npos)
      << summary;
  const auto r = Rockbench("render " + out.string() + " --out " + (dir_ / "pictures").string() +
                           " --frames --size 160x120 --to 0.2 --fps 10");
#if ROCKBENCH_HAVE_OSMESA
  ASSERT_EQ(r.exit_code, 0) << r.output;
#endif
  EXPECT_NE(r.output.find("rockbench render: note: older/ is not drawn: summary.json does not "
                          "list it"),
            std::string::npos)
      << r.output;
}

// SIGTERM to a compare whose engine started a helper in a new session (setsid) and then hangs:
// rockbench dies of SIGTERM, the helper and the engine are gone, the engine's run folder is
// removed, and a user's file and folder in --out named like rockbench's temporaries stay.
TEST_F(FailingEngineTest, SigtermEndsTheEngineAndItsSetsidHelper) {
  const fs::path helper_pid = dir_ / "helper.pid";
  const fs::path run_folder = dir_ / "run_folder.txt";
  // sh -c SCRIPT INPUT.json: $0 is the input file, in the engine's run folder.
  const std::string script = "dirname \\\"$0\\\" > " + run_folder.string() +
                             "; setsid sh -c 'echo $$ > " + helper_pid.string() +
                             "; exec sleep 60' & exec sleep 60";
  const auto scene =
      Write("scene.toml", Scene({{"sleepy", "[\"sh\", \"-c\", \"" + script + "\"]"}}));
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  std::vector<std::string> argv = {ROCKBENCH_EXE, "compare", scene.string(), "--engines",
                                   "sleepy",      "--quick", "--out",        out.string()};
  const pid_t pid = testing_util::SpawnQuiet(argv, dir_ / "err.txt");
  ASSERT_GT(pid, 0);
  // The user's files, named as rockbench's temporaries would be.
  const std::string tmp = ".tmp." + std::to_string(pid);
  std::ofstream(out / ("x" + tmp)) << "the user's";
  fs::create_directories(out / ("reference" + tmp));
  std::ofstream(out / ("reference" + tmp) / "keep.txt") << "the user's";
  int helper = -1;
  for (int i = 0; i < 1500 && helper <= 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::string text = ReadFile(helper_pid);
    if (!text.empty() && text.back() == '\n') helper = std::stoi(text);
  }
  ASSERT_GT(helper, 0) << ReadFile(dir_ / "err.txt");
  std::string folder = ReadFile(run_folder);
  while (!folder.empty() && folder.back() == '\n') folder.pop_back();
  ASSERT_TRUE(fs::is_directory(folder)) << folder;
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_NE(ReadFile(dir_ / "err.txt")
                .find("rockbench: stopped by SIGTERM: its processes ended and its temporary "
                      "files removed"),
            std::string::npos)
      << ReadFile(dir_ / "err.txt");
  // Ended before rockbench exited; its zombie is reaped by init (2 s on a loaded machine).
  for (int i = 0; i < 100 && testing_util::ProcessRuns(helper); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_FALSE(testing_util::ProcessRuns(helper)) << "the setsid helper outlived rockbench";
  if (testing_util::ProcessRuns(helper)) ::kill(helper, SIGKILL);
  EXPECT_FALSE(fs::exists(folder)) << folder;
  EXPECT_EQ(ReadFile(out / ("x" + tmp)), "the user's");
  EXPECT_EQ(ReadFile(out / ("reference" + tmp) / "keep.txt"), "the user's");
}

}  // namespace
}  // namespace rockbench
