// The wall-clock limit (util/wall_limit.h): when it fires, the process ends with exit code 3,
// says so on stderr, and leaves none of its temporary files behind; files of other processes
// and finished outputs stay.
#include "util/wall_limit.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace rockbench {
namespace {

namespace fs = std::filesystem;

TEST(WallLimit, FiresRemovesThisProcesssTemporariesAndExits3) {
  const fs::path dir = fs::temp_directory_path() / ("rockbench_wall_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "engine");
  const fs::path err = dir / "stderr.txt";
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (std::freopen(err.c_str(), "w", stderr) == nullptr) ::_exit(99);
    const std::string pid = std::to_string(::getpid());
    // A finished output, a temporary of WriteFileAtomic and one of an animation (in a
    // subfolder), and another process's temporary.
    std::ofstream(dir / "summary.json") << "{}";
    std::ofstream(dir / "engine" / ("history.csv.tmp." + pid)) << "t,theta1\n0,";
    std::ofstream(dir / (".anim.mp4.tmp" + pid)) << "partial";
    std::ofstream(dir / "other.csv.tmp.1") << "not ours";
    StartWallLimit(0.3, dir, "compare");
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
  std::ifstream in(err);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("rockbench compare: error: wall-clock limit of 0.3 s reached (--wall-limit)"),
            std::string::npos)
      << text;
  const std::string pid = std::to_string(child);
  EXPECT_FALSE(fs::exists(dir / "engine" / ("history.csv.tmp." + pid)));
  EXPECT_FALSE(fs::exists(dir / (".anim.mp4.tmp" + pid)));
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_TRUE(fs::exists(dir / "other.csv.tmp.1"));
  fs::remove_all(dir);
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
