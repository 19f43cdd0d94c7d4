// `rockbench ensemble` as a program: the same members.csv (wall times aside) at any --jobs and
// any number of MPI ranks; a crashing or hanging run becomes a row, never the end of the study;
// a study killed with SIGKILL and resumed ends with the file of one never interrupted; bad
// input exits 2 naming what is wrong; --keep-histories keeps the runs' histories.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "common/sine_pulse_block.h"

extern char** environ;

namespace rockbench {
namespace {

using testing_util::ReadFile;
using testing_util::Shell;
using CliRun = testing_util::ShellRun;

using testing_util::Rockbench;

// members.csv with its wall_s column emptied (the one column that depends on the run).
std::string WithoutWallTimes(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, out;
  int wall = -1;
  for (bool header = true; std::getline(in, line); header = false) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    if (header) {
      for (size_t i = 0; i < cells.size(); ++i) {
        if (cells[i] == "wall_s") wall = static_cast<int>(i);
      }
    } else if (wall >= 0 && wall < static_cast<int>(cells.size())) {
      cells[wall] = "";
    }
    for (size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + cells[i];
    out += "\n";
  }
  return out;
}

int Rows(const std::string& csv) {
  int n = -1;  // the header
  for (char c : csv) n += c == '\n';
  return n;
}

class EnsembleCliTest : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    // A 0.4 x 1.2 m block under a sine pulse: small amplitudes leave it at rest, middle ones
    // rock it, large ones overturn it; 2 s of simulated time.
    Write("block.toml", testing_util::SinePulseBlockToml("2.0", "[bullet]\ntime_step = 2e-4\n"));
    study_ = Write("study.toml",
                   "scene = \"block.toml\"\nengines = [\"reference\", \"bullet\"]\n"
                   "wall_limit_s = 60\n"
                   "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [0.5, 1.5, 3, 6]\n"
                   "[[axis]]\nkey = \"pulse.frequency_ratio\"\nvalues = [2, 6]\n");
  }
  std::string Out(const std::string& name) { return (dir_ / name).string(); }
  std::filesystem::path study_;
};

TEST_F(EnsembleCliTest, RowsAreTheSameAtAnyJobs) {
  const CliRun one = Rockbench("ensemble " + study_.string() + " --out " + Out("j1") + " --jobs 1");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const CliRun two = Rockbench("ensemble " + study_.string() + " --out " + Out("j2") + " --jobs 2");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  const std::string a = ReadFile(dir_ / "j1" / "members.csv");
  EXPECT_EQ(Rows(a), 16);  // 8 members x (reference, bullet)
  EXPECT_EQ(WithoutWallTimes(a), WithoutWallTimes(ReadFile(dir_ / "j2" / "members.csv")));
  // The physics spans the three outcomes: at rest, rocking, overturned.
  EXPECT_NE(a.find(",reference,at_rest,,,0,0,0,"), std::string::npos) << a;
  EXPECT_NE(a.find(",reference,overturned,1,"), std::string::npos) << a;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "j1" / "study.json"));
}

TEST_F(EnsembleCliTest, RowsAreTheSameAtOneTwoAndFourMpiRanks) {
#ifndef ROCKBENCH_MPIEXEC
  GTEST_SKIP() << "MPI was left out of this build (rockbench --version says why)";
#else
  const CliRun local =
      Rockbench("ensemble " + study_.string() + " --out " + Out("local") + " --jobs 2");
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const std::string expected = WithoutWallTimes(ReadFile(dir_ / "local" / "members.csv"));
  for (int ranks : {1, 2, 4}) {
    const std::string out = Out("mpi" + std::to_string(ranks));
    const CliRun r = Shell(std::string(ROCKBENCH_MPIEXEC) +
                           " --allow-run-as-root --oversubscribe -n " + std::to_string(ranks) +
                           // Under the sanitizers: Open MPI's components, unloaded at
                           // MPI_Finalize, leave allocations whose stacks name no library to
                           // suppress; the ranks' leak check is off (the same code without
                           // MPI is checked by the other tests).
                           " -x LSAN_OPTIONS=detect_leaks=0" + " " + ROCKBENCH_EXE + " ensemble " +
                           study_.string() + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(WithoutWallTimes(ReadFile(std::filesystem::path(out) / "members.csv")), expected)
        << ranks << " ranks";
  }
#endif
}

TEST_F(EnsembleCliTest, ACrashOrAHangIsARowNotTheEndOfTheStudy) {
  const std::string crash_study =
      Write("crash.toml",
            "scene = \"block.toml\"\nwall_limit_s = 3\n"
            "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [0.5, 1.5, 3]\n")
          .string();
  const CliRun c = Rockbench("ensemble " + crash_study + " --out " + Out("crash") +
                             " --jobs 2 --selftest-crash-member 1");
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const std::string crashed = ReadFile(dir_ / "crash" / "members.csv");
  EXPECT_EQ(Rows(crashed), 3);
  EXPECT_NE(crashed.find("\n1,1.5,,,,,,,,,,,reference,crash (signal 11),"), std::string::npos)
      << crashed;
  EXPECT_NE(crashed.find("\n2,3,"), std::string::npos);
  const CliRun h = Rockbench("ensemble " + crash_study + " --out " + Out("hang") +
                             " --jobs 1 --selftest-hang-member 0");
  ASSERT_EQ(h.exit_code, 0) << h.output;
  const std::string hung = ReadFile(dir_ / "hang" / "members.csv");
  EXPECT_EQ(Rows(hung), 3);
  EXPECT_NE(hung.find("\n0,0.5,,,,,,,,,,,reference,wall_limit,"), std::string::npos) << hung;
  EXPECT_NE(hung.find("\n1,1.5,"), std::string::npos);
}

TEST_F(EnsembleCliTest, KilledAndResumedEndsWithTheUninterruptedFile) {
  const CliRun whole =
      Rockbench("ensemble " + study_.string() + " --out " + Out("whole") + " --jobs 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  // The same study, killed (SIGKILL, no chance to tidy up) once some rows are written.
  const std::string out = Out("killed");
  std::vector<std::string> argv = {ROCKBENCH_EXE, "ensemble", study_.string(), "--out", out,
                                   "--jobs",      "1"};
  std::vector<char*> args;
  for (std::string& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  pid_t pid = -1;
  ASSERT_EQ(::posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ), 0);
  const auto start = std::chrono::steady_clock::now();
  while (Rows(ReadFile(std::filesystem::path(out) / "members.csv")) < 5 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the study ended before it was killed";
  const int before = Rows(ReadFile(std::filesystem::path(out) / "members.csv"));
  EXPECT_GE(before, 5);
  EXPECT_LT(before, 16);
  const CliRun again = Rockbench("ensemble " + study_.string() + " --out " + out);
  EXPECT_EQ(again.exit_code, 2) << again.output;  // an existing journal needs --resume
  EXPECT_NE(again.output.find("--resume"), std::string::npos) << again.output;
  const CliRun resumed =
      Rockbench("ensemble " + study_.string() + " --out " + out + " --jobs 2 --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(WithoutWallTimes(ReadFile(std::filesystem::path(out) / "members.csv")),
            WithoutWallTimes(ReadFile(dir_ / "whole" / "members.csv")));
}

TEST_F(EnsembleCliTest, BadInputExitsTwoNamingIt) {
  const CliRun missing = Rockbench("ensemble " + Out("nosuch.toml") + " --out " + Out("x"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("nosuch.toml: no such study file"), std::string::npos)
      << missing.output;
  const std::string bad = Write("bad.toml", "scene = \"block.toml\"\nengine = [\"bullet\"]\n");
  const CliRun r = Rockbench("ensemble " + bad + " --out " + Out("x"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bad.toml:2: engine: unknown key"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x"));
}

// Issue 21: an axis value out of range blamed the base scene; a NUL in `scene` printed only
// "rockbench ensemble: ". Both exit 2 before anything is made, naming the study file, line and
// key (and the axis value).
TEST_F(EnsembleCliTest, AStudysBadValueExitsTwoNamingTheStudyAndAxis) {
  const std::string range =
      Write("range.toml",
            "scene = \"block.toml\"\n[[axis]]\nkey = \"block1.width\"\nvalues = [0.2, -1]\n");
  const CliRun r = Rockbench("ensemble " + range + " --out " + Out("r"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("range.toml:2: axis block1.width = -1 (member 1: block1.width = -1): "),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "r"));
  const std::string nul = Write("nul.toml", "scene = \"blo\\u0000ck.toml\"\n");
  const CliRun n = Rockbench("ensemble " + nul + " --out " + Out("n"));
  EXPECT_EQ(n.exit_code, 2) << n.output;
  EXPECT_NE(n.output.find("nul.toml:1: scene: \"blo\\0ck.toml\" holds a control character"),
            std::string::npos)
      << n.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "n"));
}

// --memory-budget holds for every run, in the workers too: with 0.15 GiB the member of 4e5
// history rows (run.duration 200 s, output every 0.5 ms) is an error row naming the axis, the
// member's values and the estimate; the members the study's load checked pass. A smaller
// budget refuses the study when it is read.
TEST_F(EnsembleCliTest, TheMemoryBudgetReachesTheWorkers) {
  const std::string budget =
      Write("budget.toml",
            "scene = \"block.toml\"\n[[axis]]\nkey = \"run.duration\"\nvalues = [100, 200]\n"
            "[[axis]]\nkey = \"run.output_interval\"\nvalues = [1e-3, 5e-4]\n");
  const CliRun r =
      Rockbench("ensemble " + budget + " --out " + Out("b") + " --jobs 2 --memory-budget 0.15");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string rows = ReadFile(dir_ / "b" / "members.csv");
  EXPECT_EQ(Rows(rows), 4);
  // Members 0 to 2 ran; member 3's row is an error.
  EXPECT_NE(rows.find("\n2,200,0.001,"), std::string::npos) << rows;
  const size_t at3 = rows.find("\n3,200,5e-04,");
  ASSERT_NE(at3, std::string::npos) << rows;
  const std::string line3 = rows.substr(at3 + 1, rows.find('\n', at3 + 1) - at3 - 1);
  EXPECT_NE(line3.find(",reference,error,"), std::string::npos) << line3;
  EXPECT_EQ(rows.find(",reference,error,"), at3 + (line3.find(",reference,error,") + 1)) << rows;
  EXPECT_NE(rows.find("budget.toml:5: axis run.output_interval = 5e-04 (member 3: run.duration = "
                      "200; run.output_interval = 5e-04): "),
            std::string::npos)
      << rows;
  EXPECT_NE(rows.find("run.output_interval: needs an estimated"), std::string::npos) << rows;
  const CliRun small =
      Rockbench("ensemble " + budget + " --out " + Out("s") + " --memory-budget 0.1");
  EXPECT_EQ(small.exit_code, 2) << small.output;
  EXPECT_NE(small.output.find("more than the memory budget of 102 MiB"), std::string::npos)
      << small.output;
}

// The pids of this user's processes whose command line holds `needle`.
std::vector<int> ProcessesWith(const std::string& needle) {
  std::vector<int> pids;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = ReadFile(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(needle) != std::string::npos) pids.push_back(std::stoi(name));
  }
  return pids;
}

// --wall-limit stops the whole study (exit 3) with a run still hanging: its worker dies with
// the pool, members.csv keeps the rows done (a journal, resumable) and no temporary file is
// left; the study's own wall_limit_s still ends a hung run as a row (the test above).
TEST_F(EnsembleCliTest, WallLimitStopsTheStudyAndItsWorkers) {
  const std::string hang = Write("hang.toml",
                                 "scene = \"block.toml\"\nwall_limit_s = 600\n"
                                 "[[axis]]\nkey = \"pulse.amplitude_ratio\"\n"
                                 "values = [0.5, 1.5, 3]\n")
                               .string();
  const auto start = std::chrono::steady_clock::now();
  const CliRun r = Rockbench("ensemble " + hang + " --out " + Out("w") +
                             " --jobs 1 --selftest-hang-member 1 --wall-limit 2");
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("rockbench ensemble: error: wall-clock limit of 2 s reached "
                          "(--wall-limit)"),
            std::string::npos)
      << r.output;
  EXPECT_LT(took_s, 30.0);
  // The hung worker ended with its pool (PR_SET_PDEATHSIG), at once or within a moment.
  std::vector<int> left;
  for (int i = 0; i < 50; ++i) {
    left = ProcessesWith(hang + " --worker");
    if (left.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(left.empty()) << left.size() << " workers outlived the study";
  const std::string journal = ReadFile(dir_ / "w" / "members.csv");
  EXPECT_EQ(Rows(journal), 1) << journal;  // member 0's row; member 1 hung
  for (const auto& entry : std::filesystem::directory_iterator(dir_ / "w")) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  const CliRun resumed = Rockbench("ensemble " + hang + " --out " + Out("w") + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(Rows(ReadFile(dir_ / "w" / "members.csv")), 3);
}

TEST_F(EnsembleCliTest, KeepHistoriesWritesEachRunsHistory) {
  const std::string one = Write("one.toml",
                                "scene = \"block.toml\"\nengines = [\"reference\", \"bullet\"]\n"
                                "[[axis]]\nkey = \"pulse.amplitude_ratio\"\nvalues = [1.5]\n")
                              .string();
  const CliRun r = Rockbench("ensemble " + one + " --out " + Out("k") + " --keep-histories");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "k" / "members" / "0" / "reference" / "history.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "k" / "members" / "0" / "bullet" / "history.csv"));
  const CliRun plain = Rockbench("ensemble " + one + " --out " + Out("p"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "p" / "members"));
}

}  // namespace
}  // namespace rockbench
