// `rockbench sweep`: writes sweep.csv (one row per grid point) with a progress bar on stderr.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "harness/sweep.h"

namespace rockbench::cli {
namespace {

namespace fs = std::filesystem;
const fs::path kScenes = fs::path(ROCKBENCH_SOURCE_DIR) / "scenes";

TEST(CmdSweepTest, QuickSweepWritesOneRowPerRun) {
  const fs::path dir =
      fs::temp_directory_path() / ("rockbench_cmd_sweep_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  CLI::App app;
  RegisterSweep(app);
  const std::vector<std::string> args = {
      "rockbench",       "sweep",      (kScenes / "housner_free_rocking.toml").string(),
      "--out",           dir.string(), "--quick",
      "--threads",       "2",          "--set",
      "run.duration=0.3"};
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  ::testing::internal::CaptureStderr();
  app.parse(static_cast<int>(argv.size()), argv.data());
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("runs"), std::string::npos) << err;  // the progress bar
  std::ifstream f(dir / "sweep.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), SweepGrid(true, true).size() + 1);
  EXPECT_EQ(lines[0].rfind("engine,precision,time_step_s,", 0), 0u);
  for (size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].find("error"), std::string::npos) << lines[i];
  }
  // Only sweep.csv in the folder: written through a temporary name, renamed.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().filename(), "sweep.csv");
  }
  EXPECT_EQ(files, 1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rockbench::cli
