// `rockbench compare`: runs the reference and Bullet on a shipped scene and writes every file
// (histories, events, comparison.json/.csv, summary.json); bad input is a clear error.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "scene/scene.h"

namespace rockbench::cli {
namespace {

namespace fs = std::filesystem;
const fs::path kScenes = fs::path(ROCKBENCH_SOURCE_DIR) / "scenes";

std::string Slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void RunCli(std::vector<std::string> args) {
  CLI::App app;
  app.require_subcommand(1);
  RegisterCompare(app);
  args.insert(args.begin(), "rockbench");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
}

class CmdCompareTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rockbench_cmd_compare_test_" + std::to_string(getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(CmdCompareTest, WritesEveryFile) {
  RunCli({"compare", (kScenes / "housner_free_rocking.toml").string(), "--out", dir_.string(),
          "--engines", "bullet", "--set", "run.duration=1.5", "--set",
          "bullet.split_impulse_threshold=0"});
  for (const char* f :
       {"comparison.json", "comparison.csv", "summary.json", "reference/history.csv",
        "reference/events.csv", "bullet/history.csv", "bullet/events.csv"}) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / f)) << f;
  }
  const auto c = nlohmann::json::parse(Slurp(dir_ / "comparison.json"));
  const auto& b = c["engines"]["bullet"];
  EXPECT_TRUE(b["wall_s"].is_number());
  EXPECT_EQ(b["impacts_matched"], 1);  // one impact (0.698 s) in 1.5 s
  EXPECT_LT(b["theta1"]["max_abs_error_rad"].get<double>(), 1e-3);
  EXPECT_FALSE(c["engines"].contains("theta2"));
  const auto s = nlohmann::json::parse(Slurp(dir_ / "summary.json"));
  EXPECT_EQ(s["engines"]["bullet"]["settings"]["split_impulse_threshold"], 0.0);
  EXPECT_TRUE(s.contains("status"));  // the reference's part at the top, as `run` writes it
  EXPECT_EQ(Slurp(dir_ / "bullet/history.csv").rfind("t,theta1,omega1,mode\n", 0), 0u);
  // No temporary files left behind.
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
  }
}

TEST_F(CmdCompareTest, SameInputSameBytes) {
  const std::vector<std::string> args = {"compare", (kScenes / "thesis_free_rocking.toml").string(),
                                         "--out",   dir_.string(),
                                         "--set",   "run.duration=0.7",
                                         "--set",   "bullet.time_step=1e-3"};
  RunCli(args);
  const std::string csv1 = Slurp(dir_ / "bullet/history.csv");
  const std::string ev1 = Slurp(dir_ / "bullet/events.csv");
  RunCli(args);
  EXPECT_EQ(Slurp(dir_ / "bullet/history.csv"), csv1);
  EXPECT_EQ(Slurp(dir_ / "bullet/events.csv"), ev1);
  EXPECT_FALSE(ev1.empty());
}

TEST_F(CmdCompareTest, UnknownEngineIsBadInput) {
  try {
    RunCli({"compare", (kScenes / "housner_free_rocking.toml").string(), "--out", dir_.string(),
            "--engines", "mujoco"});
    ADD_FAILURE() << "accepted an unknown engine";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("mujoco"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "comparison.json"));
}

}  // namespace
}  // namespace rockbench::cli
