// `rockbench sweep`: writes sweep.csv (one row per grid point) and sweep.json, quietly when
// stderr is not a terminal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "run/engine_registry.h"
#include "sweep/sweep.h"

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
  // Progress is drawn on a terminal only: under the test, stderr is not one.
  EXPECT_EQ(err.find("runs"), std::string::npos) << err;
  std::ifstream f(dir / "sweep.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), SweepGrid(true, BuiltEngineNames()).size() + 1);
  EXPECT_EQ(lines[0].rfind("engine,family,setting,time_step_s,", 0), 0u);
  for (size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].find("error"), std::string::npos) << lines[i];
  }
  // sweep.json: the scene, its overrides and the simulated duration (the real-time mark).
  std::ifstream jf(dir / "sweep.json");
  const nlohmann::json j = nlohmann::json::parse(jf);
  EXPECT_EQ(j["scene"]["path"], (kScenes / "housner_free_rocking.toml").string());
  EXPECT_EQ(j["scene"]["overrides"][0], "run.duration=0.3");
  EXPECT_EQ(j["simulated_duration_s"], 0.3);
  EXPECT_EQ(j["options"]["threads"], 2);
  EXPECT_EQ(j["runs"], static_cast<int>(lines.size()) - 1);
  // Only sweep.csv and sweep.json in the folder: written through temporary names, renamed.
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path().filename());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"sweep.csv", "sweep.json"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rockbench::cli
