// The wall-clock limit and the termination signals (util/wall_limit.h): when either ends the
// process, every process it started (a helper that left for a session of its own included)
// ends, exactly the temporary names it registered are removed, and a user's file or folder
// merely named like one ("x.tmp.<pid>") stays, as do finished outputs and other processes'
// temporaries. The limit exits 3 with its message; a signal is died of.
#include "util/wall_limit.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "util/subprocess.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Whether process `pid` runs (a zombie, or no process, does not).
bool Running(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(in, stat)) return false;
  const size_t close = stat.rfind(')');
  return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z' &&
         stat[close + 2] != 'X';
}

// Waits up to `s` for `pid` to stop running; whether it did.
bool GoneWithin(int pid, double s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(s);
  while (Running(pid) && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return !Running(pid);
}

// Reads a pid a helper wrote (waits up to 10 s for it).
int PidFrom(const fs::path& file) {
  for (int i = 0; i < 500; ++i) {
    const std::string text = ReadAll(file);
    if (!text.empty() && text.back() == '\n') return std::stoi(text);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return -1;
}

// A scratch folder, removed at the end.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name)
      : dir(fs::temp_directory_path() / (name + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir / "engine");
  }
  ~Scratch() { fs::remove_all(dir); }
};

// In a forked child: this process's temporaries (registered) and, named like them but not
// registered, a user's file and folder; a finished output; and a helper that an "engine"
// started in a session of its own before the engine exited (sh -c 'setsid ... &'): it writes
// its pid to DIR/helper.pid.
void MakeTemporariesAndAHelper(const fs::path& dir) {
  const std::string pid = std::to_string(::getpid());
  std::ofstream(dir / "summary.json") << "{}";
  std::ofstream(dir / "engine" / ("history.csv.tmp." + pid)) << "t,theta1\n0,";
  RegisterTemporary(dir / "engine" / ("history.csv.tmp." + pid));
  fs::create_directories(dir / (".frames.tmp" + pid));
  std::ofstream(dir / (".frames.tmp" + pid) / "frame_00000.png") << "partial";
  RegisterTemporary(dir / (".frames.tmp" + pid), /*folder=*/true);
  // The decoys: a user's file and folder named like this process's temporaries.
  std::ofstream(dir / ("x.tmp." + pid)) << "the user's";
  fs::create_directories(dir / "engine" / ("notes.tmp." + pid));
  std::ofstream(dir / "engine" / ("notes.tmp." + pid) / "keep.txt") << "the user's";
  std::ofstream(dir / "other.csv.tmp.1") << "another process's";
  // The engine: starts the helper in a new session and exits at once; the helper is
  // re-parented to this process (the subreaper).
  SpawnOptions quiet;
  quiet.in = quiet.out = Stdio::kNull;
  Subprocess engine({"/bin/sh", "-c",
                     "setsid /bin/sh -c 'echo $$ > " + (dir / "helper.pid").string() +
                         "; exec sleep 60' & exit 0"},
                    quiet);
  engine.Wait();
}

// What must hold after the end: the registered names gone, the rest there, the helper ended.
void ExpectCleanedUp(const fs::path& dir, pid_t child) {
  const std::string pid = std::to_string(child);
  EXPECT_FALSE(fs::exists(dir / "engine" / ("history.csv.tmp." + pid)));
  EXPECT_FALSE(fs::exists(dir / (".frames.tmp" + pid)));
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_EQ(ReadAll(dir / ("x.tmp." + pid)), "the user's");
  EXPECT_EQ(ReadAll(dir / "engine" / ("notes.tmp." + pid) / "keep.txt"), "the user's");
  EXPECT_TRUE(fs::exists(dir / "other.csv.tmp.1"));
  const int helper = PidFrom(dir / "helper.pid");
  ASSERT_GT(helper, 0);
  // Ended by the child before it exited (2 s: the zombie's reaping by init on a loaded machine).
  EXPECT_TRUE(GoneWithin(helper, 2.0)) << "helper " << helper << " outlived its rockbench";
  if (Running(helper)) ::kill(helper, SIGKILL);
}

TEST(WallLimit, FiresEndsDescendantsRemovesOnlyRegisteredTemporariesAndExits3) {
  Scratch s("rockbench_wall_");
  const fs::path& dir = s.dir;
  const fs::path err = dir / "stderr.txt";
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (std::freopen(err.c_str(), "w", stderr) == nullptr) ::_exit(99);
    BecomeSubreaper();
    MakeTemporariesAndAHelper(dir);
    StartWallLimit(0.5, dir, "compare");
    std::this_thread::sleep_for(std::chrono::seconds(30));
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), kExitWallLimit);
  // It fired at the limit, not at the end of the 30 s sleep (10 s: a loaded machine).
  EXPECT_LT(waited, 10.0);
  const std::string text = ReadAll(err);
  EXPECT_NE(text.find("rockbench compare: error: wall-clock limit of 0.5 s reached (--wall-limit)"),
            std::string::npos)
      << text;
  ExpectCleanedUp(dir, child);
}

TEST(WallLimit, SigtermEndsDescendantsRemovesOnlyRegisteredTemporariesAndIsDiedOf) {
  Scratch s("rockbench_sigterm_");
  const fs::path& dir = s.dir;
  const fs::path err = dir / "stderr.txt";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (std::freopen(err.c_str(), "w", stderr) == nullptr) ::_exit(99);
    HandleTerminationSignals();
    BecomeSubreaper();
    MakeTemporariesAndAHelper(dir);
    std::ofstream(dir / "ready") << "1";
    std::this_thread::sleep_for(std::chrono::seconds(30));
    ::_exit(0);
  }
  for (int i = 0; i < 500 && !fs::exists(dir / "ready"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(fs::exists(dir / "ready"));
  ASSERT_EQ(::kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  const std::string text = ReadAll(err);
  EXPECT_NE(text.find("rockbench: stopped by SIGTERM: its processes ended and its temporary "
                      "files removed"),
            std::string::npos)
      << text;
  ExpectCleanedUp(dir, child);
}

// A registered name renamed into place and forgotten is not removed at the end; one a user
// holds under a name this process never registered is not either.
TEST(WallLimit, ForgottenNamesAreNotRemoved) {
  Scratch s("rockbench_forget_");
  const fs::path done = s.dir / "summary.json";
  std::ofstream(s.dir / "summary.json.tmp.9") << "{}";
  RegisterTemporary(s.dir / "summary.json.tmp.9");
  fs::rename(s.dir / "summary.json.tmp.9", done);
  ForgetTemporary(s.dir / "summary.json.tmp.9");
  // The user's file takes the forgotten name afterwards.
  std::ofstream(s.dir / "summary.json.tmp.9") << "the user's";
  EXPECT_TRUE(RegisteredTemporaries().empty());
  RemoveRegisteredTemporaries();
  EXPECT_EQ(ReadAll(s.dir / "summary.json.tmp.9"), "the user's");
  EXPECT_TRUE(fs::exists(done));
}

// No limit (0 or negative): nothing is started.
TEST(WallLimit, ZeroMeansNone) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    StartWallLimit(0.0, "", "run");
    StartWallLimit(-1.0, "", "run");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace rockbench
