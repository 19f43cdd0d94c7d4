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
  EXPECT_TRUE(b.contains("theta1"));
  EXPECT_FALSE(b.contains("theta2"));  // one block: no theta2 in the engine's agreement
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

// The verdict path: the reference with its witness, the ensembles and the verdict, written to
// comparison.json, summary.json and the ensemble CSVs; the ensembles' bytes do not depend on
// the number of threads. Rinaldi 228 cut to 6 s (theta2's horizon, 4.45 s, falls inside and
// block 2 overturns at 5.42 s), small ensembles to keep it quick.
TEST_F(CmdCompareTest, WritesTheVerdictItRestsOn) {
  const std::string scene = (kScenes / "thesis_rinaldi228.toml").string();
  const fs::path one = dir_ / "jobs1", two = dir_ / "jobs2";
  for (const auto& [out, jobs] : {std::pair{one, "1"}, std::pair{two, "2"}}) {
    // Bullet's verdict is the subject: the other engines' are the agreement suite's.
    RunCli({"compare", scene, "--out", out.string(), "--members", "8", "--engine-members", "6",
            "--jobs", jobs, "--set", "run.duration=6", "--engines", "bullet"});
  }
  const auto c = nlohmann::json::parse(Slurp(one / "comparison.json"));
  const auto& conv = c["reference"]["convergence"];
  EXPECT_TRUE(conv["converged"].get<bool>());
  EXPECT_LT(conv["max_abs_diff_rad"].get<double>(), 1e-8);
  EXPECT_EQ(conv["witness"]["rtol"], 1e-14);
  const auto& p = c["predictability"];
  EXPECT_EQ(p["members"], 8);
  ASSERT_TRUE(p["horizon_s"]["theta2"].is_number());
  EXPECT_GT(p["horizon_s"]["theta2"].get<double>(), 3.0);
  EXPECT_LT(p["horizon_s"]["theta2"].get<double>(), 5.42);
  const auto& b = c["engines"]["bullet"];
  EXPECT_FALSE(b["verdict"].get<std::string>().empty());
  EXPECT_EQ(b["verdict_kind"], "agrees") << b["verdict"];
  const auto& st = b["statistics"];
  ASSERT_TRUE(st["available"].get<bool>()) << st.dump();
  EXPECT_EQ(st["engine_members"], 6);
  for (const auto& [key, test] : st["tests"].items()) {
    if (!test["p_value"].is_number()) continue;  // e.g. no peak above the tolerance
    EXPECT_GE(test["p_value"].get<double>(), 0.0) << key;
    EXPECT_LE(test["p_value"].get<double>(), 1.0) << key;
    // The impact count is reported outside the family: no Holm p-value.
    if (!test.value("in_family", true)) {
      EXPECT_TRUE(test["p_holm"].is_null()) << key;
      continue;
    }
    EXPECT_GE(test["p_holm"].get<double>(), test["p_value"].get<double>()) << key;
  }
  const auto s = nlohmann::json::parse(Slurp(one / "summary.json"));
  EXPECT_EQ(s["convergence"]["converged"], true);
  for (const char* f :
       {"reference/ensemble_band.csv", "reference/ensemble.csv", "bullet/ensemble.csv"}) {
    EXPECT_EQ(Slurp(one / f), Slurp(two / f)) << f;
  }
  // --quick: the pointwise comparison only.
  const fs::path quick = dir_ / "quick";
  RunCli({"compare", scene, "--out", quick.string(), "--quick", "--set", "run.duration=6"});
  const auto q = nlohmann::json::parse(Slurp(quick / "comparison.json"));
  EXPECT_EQ(q["engines"]["bullet"]["verdict_kind"], "pointwise_only");
  EXPECT_FALSE(fs::exists(quick / "reference" / "ensemble_band.csv"));
}

// Issue 37 on the shipped scene whose top block slides off (mu 0.2): Bullet's block 2 leaves
// block 1 as the reference's does, an outcome of its own; block 1 never moves (its reference
// peak is ~1e-18 rad, below the floor), so the console prints no relative peak error for it
// (it printed "peak +1082123175059.36%") but the absolute one and why it is not judged point by
// point alone; the slip of each block is compared and printed.
TEST_F(CmdCompareTest, SaysOnlyTrueThingsAboutABlockThatSlidesOff) {
  ::testing::internal::CaptureStdout();
  RunCli({"compare", (kScenes / "top_block_slides_off.toml").string(), "--out", dir_.string(),
          "--engines", "bullet", "--quick"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  std::string theta1;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  bullet theta1:", 0) == 0) theta1 = line;
  }
  ASSERT_FALSE(theta1.empty()) << out;
  EXPECT_EQ(theta1.find('%'), std::string::npos) << theta1;
  EXPECT_NE(theta1.find("not judged point by point"), std::string::npos) << theta1;
  EXPECT_NE(out.find("  bullet u2 (slip): "), std::string::npos) << out;
  EXPECT_NE(out.find("leaving the support agrees"), std::string::npos) << out;
  const auto c = nlohmann::json::parse(Slurp(dir_ / "comparison.json"));
  const auto& b = c["engines"]["bullet"];
  EXPECT_EQ(c["reference"]["status"], "left_support");
  EXPECT_EQ(b["status"], "left_support");
  EXPECT_FALSE(b["theta1"]["judged"].get<bool>());
  EXPECT_TRUE(b["theta2"]["judged"].get<bool>());
  EXPECT_TRUE(b["left_support"]["agree"].get<bool>());
  EXPECT_EQ(b["left_support"]["reference_block"], 2);
  EXPECT_TRUE(b["overturn"]["agree"].get<bool>());
  EXPECT_TRUE(b["overturn"]["engine_block"].is_null());
  for (const char* key :
       {"max_abs_error_m", "final_reference_m", "final_engine_m", "tolerance_m"}) {
    EXPECT_TRUE(b["u2"][key].is_number()) << key;
  }
  EXPECT_EQ(b["verdict_kind"], "pointwise_only") << b["verdict"];
}

// An undetermined impact (issue 37): scenes/three_blocks_undetermined.toml run for 4 s (the
// reference's block 3 overturns at 3.569 s on the branch its rule chose, after the impact at
// 2.642351 s whose two outcomes give different motions). compare says UNDETERMINED on its console
// and stderr, writes every output, exits 5 as run does, and compares no outcome after that
// instant: neither run's overturn (both later) is compared, and the line says up to when.
TEST_F(CmdCompareTest, AnUndeterminedReferenceIsSaidAndNoOutcomeIsComparedAfterIt) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  int code = 0;
  try {
    RunCli({"compare", (kScenes / "three_blocks_undetermined.toml").string(), "--out",
            dir_.string(), "--engines", "bullet", "--quick", "--set", "run.duration=4"});
  } catch (const CLI::RuntimeError& e) {
    code = e.get_exit_code();
  }
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, kExitUndetermined) << out << err;
  EXPECT_NE(out.find("  UNDETERMINED from 2.6424 s: the interface2 impact"), std::string::npos)
      << out;
  EXPECT_NE(out.find("overturning agrees up to 2.6424 s (the model does not decide after it)"),
            std::string::npos)
      << out;
  EXPECT_NE(err.find("the model stops deciding the motion at t = 2.6424 s"), std::string::npos)
      << err;
  const auto c = nlohmann::json::parse(Slurp(dir_ / "comparison.json"));
  const auto& b = c["engines"]["bullet"];
  EXPECT_NEAR(b["compared_until_s"].get<double>(), 2.642351, 1e-6);
  // The reference's overturn (block 3 at 3.569 s) is after the undetermined instant.
  EXPECT_TRUE(b["overturn"]["reference_block"].is_null()) << b["overturn"];
  EXPECT_TRUE(b["overturn"]["agree"].get<bool>());
  EXPECT_EQ(b["verdict_kind"], "outside_model") << b["verdict"];
}

TEST_F(CmdCompareTest, UnknownEngineIsBadInput) {
  try {
    RunCli({"compare", (kScenes / "housner_free_rocking.toml").string(), "--out", dir_.string(),
            "--engines", "bullet,mujocco"});
    ADD_FAILURE() << "accepted an unknown engine";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown engine 'mujocco'"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "comparison.json"));
}

}  // namespace
}  // namespace rockbench::cli
