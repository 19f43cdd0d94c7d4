// Child processes (util/subprocess.h). RunProcess: output capture, exit codes, signals, the
// wall-clock limit, stdin, working folder. Subprocess: exit codes and signals with their text,
// pipes both ways (the study workers' line protocol), captured standard error (ffmpeg's
// messages), a log file for standard error, a child that dies with its parent, start errors.
// SelfExecutable, BesideSelf and FindProgram.
#include "util/subprocess.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace rockbench {
namespace {

ProcessOptions WithStdin(const std::string& text) {
  ProcessOptions o;
  o.stdin_text = text;
  return o;
}
ProcessOptions WithTimeout(double s) {
  ProcessOptions o;
  o.timeout_s = s;
  return o;
}
ProcessOptions InFolder(const std::string& dir) {
  ProcessOptions o;
  o.working_dir = dir;
  return o;
}

TEST(RunProcess, CapturesBothOutputsAndTheExitCode) {
  const ProcessResult r = RunProcess({"sh", "-c", "echo out; echo err >&2; exit 3"});
  ASSERT_TRUE(r.started) << r.start_error;
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.signal, 0);
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.out, "out\n");
  EXPECT_EQ(r.err, "err\n");
  EXPECT_FALSE(r.ok());
}

TEST(RunProcess, PassesStandardInputThrough) {
  // 1 MB: larger than a pipe's buffer, so writing and reading must interleave.
  const std::string text(1 << 20, 'x');
  const ProcessResult r = RunProcess({"cat"}, WithStdin(text));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.out.size(), text.size());
  EXPECT_EQ(r.out, text);
}

TEST(RunProcess, KillsAChildAtTheWallClockLimit) {
  const ProcessResult r = RunProcess({"sleep", "30"}, WithTimeout(0.3));
  ASSERT_TRUE(r.started);
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.signal, SIGKILL);
  EXPECT_EQ(r.exit_code, -1);
  EXPECT_LT(r.wall_s, 10.0);
}

TEST(RunProcess, KillsAChildThatClosedItsOutputsButRunsOn) {
  const ProcessResult r =
      RunProcess({"sh", "-c", "exec >/dev/null 2>&1; sleep 30"}, WithTimeout(0.3));
  EXPECT_TRUE(r.timed_out);
  EXPECT_LT(r.wall_s, 10.0);
}

TEST(RunProcess, ReportsTheSignalThatEndedTheChild) {
  const ProcessResult r = RunProcess({"sh", "-c", "kill -SEGV $$"});
  EXPECT_EQ(r.signal, SIGSEGV);
  EXPECT_FALSE(r.timed_out);
}

TEST(RunProcess, RunsInTheGivenFolder) {
  const ProcessResult r = RunProcess({"pwd"}, InFolder("/tmp"));
  EXPECT_EQ(r.out, "/tmp\n");
}

TEST(RunProcess, SaysWhyAMissingProgramDidNotStart) {
  const ProcessResult r = RunProcess({"/nonexistent/program"});
  EXPECT_FALSE(r.started);
  EXPECT_NE(r.start_error.find("/nonexistent/program"), std::string::npos);
  const ProcessResult p = RunProcess({"rockbench-no-such-program-on-path"});
  EXPECT_FALSE(p.started);
}

namespace fs = std::filesystem;

// A fresh folder for one test's files.
fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("rockbench_subprocess_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// One line from a child's stdout pipe (without the newline); empty at end of output.
std::string ReadLine(int fd) {
  std::string line;
  char c = 0;
  while (::read(fd, &c, 1) == 1 && c != '\n') line += c;
  return line;
}

SpawnOptions Options(Stdio in, Stdio out, Stdio err) {
  SpawnOptions o;
  o.in = in;
  o.out = out;
  o.err = err;
  return o;
}

TEST(ExitStatus, SaysTheExitStatusOrTheSignal) {
  EXPECT_EQ((ExitStatus{3, 0}).Text(), "exit status 3");
  EXPECT_EQ((ExitStatus{-1, 9}).Text(), "signal 9");
  EXPECT_TRUE((ExitStatus{0, 0}).ok());
  EXPECT_FALSE((ExitStatus{-1, 9}).ok());
}

TEST(Subprocess, ReportsTheExitCode) {
  for (const bool die_with_parent : {false, true}) {
    SpawnOptions o;
    o.die_with_parent = die_with_parent;
    Subprocess p({"sh", "-c", "exit 7"}, o);
    ASSERT_TRUE(p.started()) << p.start_error();
    EXPECT_TRUE(p.running());
    EXPECT_GT(p.pid(), 0);
    const ExitStatus s = p.Wait();
    EXPECT_EQ(s.exit_code, 7);
    EXPECT_EQ(s.signal, 0);
    EXPECT_EQ(s.Text(), "exit status 7");
    EXPECT_FALSE(p.running());
    EXPECT_EQ(p.Wait().exit_code, 7);  // again: the same answer
  }
  Subprocess ok({"true"}, SpawnOptions{});
  EXPECT_TRUE(ok.Wait().ok());
}

TEST(Subprocess, ReportsTheSignalThatEndedIt) {
  Subprocess self_killed({"sh", "-c", "kill -TERM $$"}, SpawnOptions{});
  const ExitStatus s = self_killed.Wait();
  EXPECT_EQ(s.signal, SIGTERM);
  EXPECT_EQ(s.exit_code, -1);
  EXPECT_EQ(s.Text(), "signal " + std::to_string(SIGTERM));

  Subprocess sleeper({"sleep", "30"}, SpawnOptions{});
  EXPECT_FALSE(sleeper.TryWait().has_value());  // still running
  sleeper.Kill();
  EXPECT_EQ(sleeper.Wait().signal, SIGKILL);
  sleeper.Kill();  // no effect once waited for
}

TEST(Subprocess, TryWaitSeesTheEndWithoutBlocking) {
  Subprocess p({"sh", "-c", "exit 4"}, SpawnOptions{});
  std::optional<ExitStatus> s;
  const auto start = std::chrono::steady_clock::now();
  while (!(s = p.TryWait()) &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(30)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->exit_code, 4);
  EXPECT_EQ(p.Wait().exit_code, 4);
}

TEST(Subprocess, PipesRoundTripLineByLine) {
  // The study workers' protocol: a line in, a line back, many times over one pair of pipes.
  Subprocess p({"cat"}, Options(Stdio::kPipe, Stdio::kPipe, Stdio::kInherit));
  ASSERT_TRUE(p.started()) << p.start_error();
  ASSERT_GE(p.stdin_fd(), 0);
  ASSERT_GE(p.stdout_fd(), 0);
  EXPECT_EQ(p.stderr_fd(), -1);
  for (int i = 0; i < 100; ++i) {
    const std::string line = std::to_string(i) + " " + std::to_string(i % 3);
    ASSERT_EQ(p.WriteStdin(line + "\n"), 0);
    EXPECT_EQ(ReadLine(p.stdout_fd()), line);
  }
  p.CloseStdin();  // cat ends at end of input
  EXPECT_EQ(ReadLine(p.stdout_fd()), "");
  EXPECT_TRUE(p.Wait().ok());
  EXPECT_EQ(p.stdin_fd(), -1);
  EXPECT_EQ(p.stdout_fd(), -1);
}

TEST(Subprocess, WritingToAChildThatStoppedReadingIsAnErrorNotTheEnd) {
  // The child closes its input, says so, and lives on: our write gets EPIPE, no SIGPIPE.
  // (exec: the sleep is the child that is killed, not a grandchild left holding the pipes.)
  Subprocess p({"sh", "-c", "exec 0<&-; echo closed; exec sleep 30"},
               Options(Stdio::kPipe, Stdio::kPipe, Stdio::kInherit));
  ASSERT_EQ(ReadLine(p.stdout_fd()), "closed");
  const std::string big(1 << 20, 'x');
  EXPECT_EQ(p.WriteStdin(big), EPIPE);
  p.Kill();
  EXPECT_EQ(p.Wait().signal, SIGKILL);
}

TEST(Subprocess, CapturesStandardErrorWhileTheCallerWrites) {
  // ffmpeg's case: frames in on stdin, messages out on stderr, more than a pipe holds.
  SpawnOptions o = Options(Stdio::kPipe, Stdio::kNull, Stdio::kCapture);
  Subprocess p(
      {"sh", "-c", "head -c 300000 /dev/zero | tr '\\0' e >&2; cat; echo done >&2; exit 2"}, o);
  ASSERT_TRUE(p.started()) << p.start_error();
  EXPECT_EQ(p.stderr_fd(), -1);  // read by the Subprocess's own thread
  const std::string frame(100000, 'f');
  for (int i = 0; i < 10; ++i) ASSERT_EQ(p.WriteStdin(frame), 0);
  const ExitStatus s = p.Wait();
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_EQ(p.captured_err().size(), 300000u + 5u);
  EXPECT_EQ(p.captured_err().substr(p.captured_err().size() - 5), "done\n");
  EXPECT_TRUE(p.captured_out().empty());
}

TEST(Subprocess, KeepsTheLastBytesOfACapturedStream) {
  SpawnOptions o = Options(Stdio::kInherit, Stdio::kCapture, Stdio::kCapture);
  o.capture_limit_bytes = 4;
  Subprocess p({"sh", "-c", "echo 123456789; echo abcdefgh >&2"}, o);
  p.Wait();
  EXPECT_EQ(p.captured_out(), "789\n");
  EXPECT_EQ(p.captured_err(), "fgh\n");
}

TEST(Subprocess, AppendsStandardErrorToALogFile) {
  const fs::path dir = Scratch("log");
  SpawnOptions o;
  o.err_log = dir / "workers.log";
  Subprocess a({"sh", "-c", "echo first >&2"}, o);
  EXPECT_TRUE(a.Wait().ok());
  Subprocess b({"sh", "-c", "echo second >&2"}, o);
  EXPECT_TRUE(b.Wait().ok());
  EXPECT_EQ(ReadFile(o.err_log), "first\nsecond\n");
  // A log that cannot be opened: not started, naming the file.
  o.err_log = dir / "no_such_folder" / "workers.log";
  Subprocess c({"true"}, o);
  EXPECT_FALSE(c.started());
  EXPECT_NE(c.start_error().find(o.err_log.string() + ": cannot open: "), std::string::npos)
      << c.start_error();
  EXPECT_EQ(c.Wait().exit_code, -1);
  fs::remove_all(dir);
}

TEST(Subprocess, RunsInTheGivenFolder) {
  SpawnOptions o = Options(Stdio::kNull, Stdio::kCapture, Stdio::kInherit);
  o.working_dir = "/tmp";
  Subprocess p({"pwd"}, o);
  p.Wait();
  EXPECT_EQ(p.captured_out(), "/tmp\n");
}

TEST(Subprocess, SaysWhyAMissingProgramDidNotStart) {
  for (const bool die_with_parent : {false, true}) {
    SpawnOptions o;
    o.die_with_parent = die_with_parent;
    Subprocess p({"/nonexistent/program"}, o);
    EXPECT_FALSE(p.started());
    EXPECT_FALSE(p.running());
    EXPECT_EQ(p.start_error(), "/nonexistent/program: No such file or directory");
    Subprocess q({"rockbench-no-such-program-on-path"}, o);
    EXPECT_FALSE(q.started());
    EXPECT_EQ(q.start_error(), "rockbench-no-such-program-on-path: No such file or directory");
    // Not a program: a folder.
    Subprocess r({"/tmp"}, o);
    EXPECT_FALSE(r.started());
    EXPECT_NE(r.start_error().find("/tmp: "), std::string::npos) << r.start_error();
  }
  EXPECT_EQ(Subprocess({}, SpawnOptions{}).start_error(), "no program given");
}

TEST(Subprocess, MovesAndKillsWhatItOwnsWhenDestroyed) {
  pid_t pid = -1;
  {
    std::vector<Subprocess> children;
    children.emplace_back(std::vector<std::string>{"sleep", "30"}, SpawnOptions{});
    Subprocess moved = std::move(children.back());
    pid = moved.pid();
    ASSERT_GT(pid, 0);
    children.back() = Subprocess();
    EXPECT_TRUE(moved.running());
  }
  // Destroyed: killed and reaped (no zombie left: the pid is no child of ours any more).
  EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD);
}

TEST(Subprocess, AChildThatDiesWithItsParentEndsWhenTheParentDoes) {
  // A process of ours starts `sleep 30` asking for die_with_parent, tells us its pid, and ends
  // without killing it: the sleep must end too.
  int report[2];
  ASSERT_EQ(::pipe(report), 0);
  const pid_t parent = ::fork();
  ASSERT_GE(parent, 0);
  if (parent == 0) {
    ::close(report[0]);
    SpawnOptions o;
    o.die_with_parent = true;
    auto* p = new Subprocess({"sleep", "30"}, o);  // never destroyed: no kill from us
    const pid_t child = p->pid();
    (void)!::write(report[1], &child, sizeof child);
    ::_exit(0);
  }
  ::close(report[1]);
  pid_t child = -1;
  ASSERT_EQ(::read(report[0], &child, sizeof child), static_cast<ssize_t>(sizeof child));
  ::close(report[0]);
  ASSERT_GT(child, 0);
  ::waitpid(parent, nullptr, 0);
  // Gone (or a zombie waiting for init) within a few seconds.
  bool ended = false;
  for (int i = 0; i < 500 && !ended; ++i) {
    const std::string stat = ReadFile("/proc/" + std::to_string(child) + "/stat");
    const size_t close = stat.rfind(')');
    ended = stat.empty() || (close != std::string::npos && stat.compare(close + 2, 1, "Z") == 0);
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(ended) << "sleep " << child << " outlived its parent";
  if (!ended) ::kill(child, SIGKILL);
}

TEST(SelfExecutable, IsThisTestAndBesideSelfIsItsFolder) {
  const fs::path self = SelfExecutable();
  EXPECT_EQ(self.filename(), "util_subprocess_test");
  EXPECT_TRUE(fs::is_regular_file(self));
  EXPECT_EQ(BesideSelf("rockbench-bullet-float"), self.parent_path() / "rockbench-bullet-float");
}

TEST(FindProgram, SearchesPathAndTakesAPathAsItIs) {
  const std::optional<fs::path> sh = FindProgram("sh");
  ASSERT_TRUE(sh.has_value());
  EXPECT_TRUE(sh->is_absolute());
  EXPECT_EQ(FindProgram(sh->string()), *sh);
  EXPECT_FALSE(FindProgram("rockbench-no-such-program-on-path").has_value());
  EXPECT_FALSE(FindProgram("/tmp").has_value());  // a folder is no program
  EXPECT_FALSE(FindProgram("/nonexistent/program").has_value());
}

}  // namespace
}  // namespace rockbench
