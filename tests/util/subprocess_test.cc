// RunProcess: output capture, exit codes, signals, the wall-clock limit, stdin, working folder.
#include "util/subprocess.h"

#include <gtest/gtest.h>
#include <signal.h>

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

}  // namespace
}  // namespace rockbench
