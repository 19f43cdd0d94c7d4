// `rockbench ensemble --resume` keeps a study folder's finished rows (issue 38): a blank line, a
// line that is not a row, a last line cut short, an edited study and a second writer. Every
// finished row survives a resume or the resume is refused naming the line (and the file is left
// as it was); a second writer is refused naming the folder and the first's pid; SIGTERM to a
// running study ends its workers and leaves no temporary name of its own.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "common/sine_pulse_block.h"
#include "common/spawn_quiet.h"

extern char** environ;

namespace rockbench {
namespace {

namespace fs = std::filesystem;
using testing_util::ReadFile;
using testing_util::Rockbench;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l + "\n");
  return out;
}

std::string Join(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l;
  return s;
}

// The index of the column named `name` in members.csv's header.
size_t Column(const std::string& header, const std::string& name) {
  std::stringstream ss(header.substr(0, header.size() - 1));
  size_t k = 0;
  for (std::string c; std::getline(ss, c, ','); ++k) {
    if (c == name) return k;
  }
  return std::string::npos;
}

// `line` with cell `column` set to `value`.
std::string WithCell(const std::string& line, size_t column, const std::string& value) {
  std::vector<std::string> cells;
  size_t start = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == ',' || line[i] == '\n') {
      cells.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  cells[column] = value;
  std::string out;
  for (size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + cells[i];
  return out + "\n";
}

// The processes whose parent is `pid`.
std::vector<int> ChildrenOf(int pid) {
  std::vector<int> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "stat");
    std::string stat;
    if (!std::getline(in, stat)) continue;
    const size_t close = stat.rfind(')');
    if (close == std::string::npos || stat[close + 2] == 'Z') continue;
    if (std::atoi(stat.c_str() + close + 4) == pid) out.push_back(std::stoi(name));
  }
  return out;
}

class ResumeTest : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    // A 0.4 x 1.2 m block under a 2 Hz sine pulse for 0.5 s: the reference alone, six members.
    Write("block.toml", testing_util::SinePulseBlockToml("0.5"));
    study_ = Write("study.toml", StudyText("0.1, 0.2, 0.3, 0.4, 0.5, 0.6")).string();
    out_ = dir_ / "out";
    const auto r = Rockbench("ensemble " + study_ + " --out " + out_.string() + " --jobs 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    finished_ = Lines(ReadFile(out_ / "members.csv"));
    ASSERT_EQ(finished_.size(), 7u);
    wall_ = Column(finished_[0], "wall_s");
    ASSERT_NE(wall_, std::string::npos);
    // Every row marked with a wall time no run takes: a row made again loses its mark.
    for (size_t k = 1; k < finished_.size(); ++k) {
      finished_[k] = WithCell(finished_[k], wall_, "123.5");
    }
  }
  static std::string StudyText(const std::string& values) {
    return "scene = \"block.toml\"\nengines = [\"reference\"]\n"
           "[[axis]]\nkey = \"base.horizontal.amplitude_g\"\nvalues = [" +
           values + "]\n";
  }
  testing_util::ShellRun Resume() {
    return Rockbench("ensemble " + study_ + " --out " + out_.string() + " --jobs 2 --resume");
  }
  // Rows kept from before the resume (their mark is there).
  int MarkedRows() {
    int n = 0;
    for (const std::string& l : Lines(ReadFile(out_ / "members.csv"))) {
      n += l.find(",123.5,") != std::string::npos;
    }
    return n;
  }
  std::string study_;
  fs::path out_;
  std::vector<std::string> finished_;
  size_t wall_ = 0;
};

// A blank line in the middle: skipped and said; the rows after it are kept, not made again.
TEST_F(ResumeTest, ABlankLineKeepsTheRowsAfterIt) {
  std::vector<std::string> file(finished_.begin(), finished_.end() - 1);  // member 5 to do
  file.insert(file.begin() + 3, "\n");
  std::ofstream(out_ / "members.csv", std::ios::binary) << Join(file);
  const auto r = Resume();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("members.csv:4: a blank line, skipped"), std::string::npos) << r.output;
  EXPECT_EQ(MarkedRows(), 5);  // members 0-4; member 5 made now
  EXPECT_EQ(Lines(ReadFile(out_ / "members.csv")).size(), 7u);
}

// A line that is not a row: refused naming it; the file is left as it was.
TEST_F(ResumeTest, AGarbageLineIsRefusedNamingIt) {
  std::vector<std::string> file(finished_.begin(), finished_.end() - 1);
  file.insert(file.begin() + 2, "hello, world\n");
  const std::string before = Join(file);
  std::ofstream(out_ / "members.csv", std::ios::binary) << before;
  const auto r = Resume();
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("members.csv:3: not a row of this study: 2 cells"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("no row was dropped"), std::string::npos) << r.output;
  EXPECT_EQ(ReadFile(out_ / "members.csv"), before);
}

// A last line cut short by a kill: only it is removed, its run made again, every other row kept.
TEST_F(ResumeTest, ALastLineCutShortIsMadeAgain) {
  std::vector<std::string> file(finished_.begin(), finished_.end() - 1);
  const std::string last = finished_.back();
  const std::string before = Join(file) + last.substr(0, last.size() / 2);
  std::ofstream(out_ / "members.csv", std::ios::binary) << before;
  const auto r = Resume();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("members.csv:7: the last line is cut short"), std::string::npos)
      << r.output;
  EXPECT_EQ(MarkedRows(), 5);
  const std::vector<std::string> after = Lines(ReadFile(out_ / "members.csv"));
  ASSERT_EQ(after.size(), 7u);
  // Member 5's row made again is the finished one (wall time aside).
  EXPECT_EQ(WithCell(after[6], wall_, "123.5"), last);
  // A last line that is no row's beginning is refused, the file untouched.
  const std::string junk = Join(file) + "#note";
  std::ofstream(out_ / "members.csv", std::ios::binary) << junk;
  const auto j = Resume();
  EXPECT_EQ(j.exit_code, 2) << j.output;
  EXPECT_NE(j.output.find("members.csv:7: a last line without its end that is not the "
                          "beginning of a row (#note)"),
            std::string::npos)
      << j.output;
  EXPECT_EQ(ReadFile(out_ / "members.csv"), junk);
}

// A second row of one run (two writers before the lock): the first is kept, the study finishes
// with one row per run.
TEST_F(ResumeTest, ASecondRowOfARunIsSkipped) {
  std::vector<std::string> file(finished_.begin(), finished_.end() - 1);
  file.push_back(WithCell(finished_[2], wall_, "7"));
  std::ofstream(out_ / "members.csv", std::ios::binary) << Join(file);
  const auto r = Resume();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("members.csv:7: a second row of member 1, engine reference (line 3 is "
                          "kept), skipped"),
            std::string::npos)
      << r.output;
  const std::vector<std::string> after = Lines(ReadFile(out_ / "members.csv"));
  ASSERT_EQ(after.size(), 7u);
  EXPECT_EQ(after[2], finished_[2]);
}

// An edited study: an axis's values, or the base scene, differ from the rows': refused naming
// the row or the input; nothing is changed.
TEST_F(ResumeTest, AnEditedStudyIsRefused) {
  std::vector<std::string> file(finished_.begin(), finished_.end() - 1);
  const std::string before = Join(file);
  std::ofstream(out_ / "members.csv", std::ios::binary) << before;
  Write("study.toml", StudyText("0.1, 0.25, 0.3, 0.4, 0.5, 0.6"));
  const auto a = Resume();
  EXPECT_EQ(a.exit_code, 2) << a.output;
  EXPECT_NE(a.output.find("members.csv:3: member 1 (reference) was run with "
                          "base.horizontal.amplitude_g = 0.2, the study gives it 0.25 now"),
            std::string::npos)
      << a.output;
  EXPECT_EQ(ReadFile(out_ / "members.csv"), before);
  // The axes as they were, the block taller: the rows' columns cannot show it; members.study
  // does.
  Write("study.toml", StudyText("0.1, 0.2, 0.3, 0.4, 0.5, 0.6"));
  Write("block.toml",
        "[block1]\nwidth = 0.4\nheight = 1.5\ndensity = 2000.0\n"
        "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\nfrequency_hz = 2.0\n"
        "[run]\nduration = 0.5\n");
  const auto b = Resume();
  EXPECT_EQ(b.exit_code, 2) << b.output;
  EXPECT_NE(b.output.find("members.study:2: scene_bytes_fnv1a64 = "), std::string::npos)
      << b.output;
  EXPECT_NE(b.output.find("the study was edited since"), std::string::npos) << b.output;
  EXPECT_EQ(ReadFile(out_ / "members.csv"), before);
}

// Two writers: while a study runs (its worker hangs on member 0), a --resume of its folder is
// refused naming the folder and the running study's pid. SIGTERM then ends the study, its
// workers with it, and leaves no temporary name; the resume then finishes the study.
TEST_F(ResumeTest, ASecondWriterIsRefusedAndSigtermEndsTheWorkers) {
  std::ofstream(out_ / "members.csv", std::ios::binary)
      << Join(std::vector<std::string>(finished_.begin(), finished_.begin() + 2));
  // A user's files named like the study's temporaries.
  std::ofstream(out_ / "members.csv.tmp.1") << "the user's";
  std::vector<std::string> argv = {ROCKBENCH_EXE,
                                   "ensemble",
                                   study_,
                                   "--out",
                                   out_.string(),
                                   "--jobs",
                                   "1",
                                   "--resume",
                                   "--selftest-hang-member",
                                   "1"};
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, (dir_ / "first.err").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t first = -1;
  ASSERT_EQ(::posix_spawn(&first, cargs[0], &actions, nullptr, cargs.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Until the first holds the lock and its worker runs member 1.
  std::vector<int> workers;
  for (int i = 0; i < 1000 && workers.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (ReadFile(out_ / "members.lock") == std::to_string(first) + "\n")
      workers = ChildrenOf(first);
  }
  ASSERT_FALSE(workers.empty()) << ReadFile(dir_ / "first.err");
  const auto second = Resume();
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find(out_.string() + ": another rockbench ensemble (pid " +
                               std::to_string(first) + ") is writing this study folder"),
            std::string::npos)
      << second.output;
  ASSERT_EQ(::kill(first, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(first, &status, 0), first);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  for (const int w : workers) {
    EXPECT_FALSE(testing_util::ProcessRuns(w))
        << "worker " << w
        << " outlived the study: " << ReadFile("/proc/" + std::to_string(w) + "/stat")
        << ReadFile("/proc/" + std::to_string(w) + "/cmdline");
  }
  for (const auto& e : fs::recursive_directory_iterator(out_)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp." + std::to_string(first)), std::string::npos) << name;
  }
  EXPECT_EQ(ReadFile(out_ / "members.csv.tmp.1"), "the user's");
  const auto done = Resume();
  ASSERT_EQ(done.exit_code, 0) << done.output;
  EXPECT_EQ(Lines(ReadFile(out_ / "members.csv")).size(), 7u);
}

}  // namespace
}  // namespace rockbench
