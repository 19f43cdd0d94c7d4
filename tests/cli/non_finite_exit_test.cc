// `rockbench run` and `rockbench compare` when a run ends non_finite (issue 21, item 1): the
// subcommand writes its outputs, each ending at its run's last finite state with no NaN or
// infinity in them, names every failed run on stderr and exits with kExitRunFailed (4).
//
// No scene the readers accept reaches a non-finite state (their limits refuse absurd inputs up
// front, docs/limits.md), so the test swaps an absurd base motion in after the scene is read:
// the link wraps GroundMotion::FromScene (-Wl,--wrap, tests/cli/CMakeLists.txt), and the wrapper
// replaces the horizontal component with a 1e200 g spike when a test asks for it. Everything
// else is the subcommand as registered, in process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "motion/ground_motion.h"
#include "scene/scene.h"
#include "tests/common/json_checks.h"

namespace {

// Whether the wrapped GroundMotion::FromScene returns the absurd motion.
bool g_absurd_motion = false;

}  // namespace

// GroundMotion::FromScene(const Scene&), as the linker names it.
extern "C" rockbench::GroundMotion __real__ZN9rockbench12GroundMotion9FromSceneERKNS_5SceneE(
    const rockbench::Scene& scene);

// The scene's motion, or a 2 s record, zero but for one sample of 1e200 g at 0.50 s (the
// acceleration ramps up from 0.49 s): the reference's and the engines' states overflow there.
extern "C" rockbench::GroundMotion __wrap__ZN9rockbench12GroundMotion9FromSceneERKNS_5SceneE(
    const rockbench::Scene& scene) {
  rockbench::GroundMotion m = __real__ZN9rockbench12GroundMotion9FromSceneERKNS_5SceneE(scene);
  if (g_absurd_motion) {
    std::vector<double> a(200, 0.0);
    a[50] = 1e200 * 9.80665;
    m.set_horizontal(rockbench::MotionComponent::FromSamples(std::move(a), 0.01, 0.0, "spike"));
  }
  return m;
}

namespace rockbench::cli {
namespace {

namespace fs = std::filesystem;
const fs::path kScene = fs::path(ROCKBENCH_SOURCE_DIR) / "scenes" / "thesis_free_rocking.toml";

std::string Slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A CSV written by rockbench holds no field that reads as a number that is not finite ("nan",
// "inf", "-inf"; a note's words, such as "energy is +inf at t = ...", are not numbers).
bool CsvFinite(const fs::path& p) {
  std::istringstream text(Slurp(p));
  std::string line, field;
  int lines = 0;
  while (std::getline(text, line)) {
    ++lines;
    std::istringstream fields(line);
    while (std::getline(fields, field, ',')) {
      char* end = nullptr;
      const double v = std::strtod(field.c_str(), &end);
      if (end != field.c_str() && *end == '\0' && !std::isfinite(v)) return false;
    }
  }
  return lines > 1;
}

struct CliResult {
  int exit_code = 0;   // what main() would return: 0, or the subcommand's CLI::RuntimeError
  std::string stderr;  // what it printed on stderr
};

CliResult RunCli(std::vector<std::string> args) {
  CLI::App app;
  app.require_subcommand(1);
  RegisterRun(app);
  RegisterCompare(app);
  args.insert(args.begin(), "rockbench");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  CliResult r;
  testing::internal::CaptureStderr();
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::RuntimeError& e) {
    r.exit_code = e.get_exit_code();
  }
  r.stderr = testing::internal::GetCapturedStderr();
  return r;
}

class NonFiniteExitTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rockbench_non_finite_exit_" + std::to_string(getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override {
    g_absurd_motion = false;
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(NonFiniteExitTest, RunExitsWithRunFailedAndWritesOnlyTheComputedPart) {
  g_absurd_motion = true;
  const CliResult r = RunCli({"run", kScene.string(), "--out", dir_.string(), "--engine",
                              "reference", "--engine", "bullet", "--set", "run.duration=1"});
  EXPECT_EQ(r.exit_code, kExitRunFailed);
  EXPECT_NE(r.stderr.find("rockbench: run failed: reference: "), std::string::npos) << r.stderr;
  EXPECT_NE(r.stderr.find("rockbench: run failed: bullet: "), std::string::npos) << r.stderr;
  const auto s = nlohmann::json::parse(Slurp(dir_ / "summary.json"));
  EXPECT_EQ(s["status"], "non_finite");
  EXPECT_EQ(s["engines"]["bullet"]["status"], "non_finite");
  // Where the motion's absurd part starts (0.49 s), to the sample it peaks at.
  for (const nlohmann::json* part : {&s, &s["engines"]["bullet"]}) {
    const double t = (*part)["non_finite"]["t_s"].get<double>();
    EXPECT_GT(t, 0.49 - 1e-9);
    EXPECT_LE(t, 0.50 + 1e-9);
  }
  EXPECT_TRUE(testing_util::AllFinite(s)) << s.dump(2);
  for (const char* f : {"reference/history.csv", "reference/events.csv", "bullet/history.csv",
                        "bullet/events.csv"}) {
    EXPECT_TRUE(CsvFinite(dir_ / f)) << f;
  }
  EXPECT_NE(Slurp(dir_ / "reference/events.csv").find(",non_finite,"), std::string::npos);
}

TEST_F(NonFiniteExitTest, RunOfTheSameSceneWithItsOwnMotionExitsZero) {
  const CliResult r = RunCli({"run", kScene.string(), "--out", dir_.string(), "--engine",
                              "reference", "--set", "run.duration=1"});
  EXPECT_EQ(r.exit_code, 0) << r.stderr;
  EXPECT_EQ(nlohmann::json::parse(Slurp(dir_ / "summary.json"))["status"], "completed");
}

TEST_F(NonFiniteExitTest, CompareExitsWithRunFailedAndStatesNoAgreement) {
  g_absurd_motion = true;
  const CliResult r = RunCli({"compare", kScene.string(), "--out", dir_.string(), "--engines",
                              "bullet", "--set", "run.duration=1"});
  EXPECT_EQ(r.exit_code, kExitRunFailed);
  EXPECT_NE(r.stderr.find("rockbench: compare failed: reference: "), std::string::npos) << r.stderr;
  EXPECT_NE(r.stderr.find("rockbench: compare failed: bullet: "), std::string::npos) << r.stderr;
  const auto c = nlohmann::json::parse(Slurp(dir_ / "comparison.json"));
  EXPECT_EQ(c["reference"]["status"], "non_finite");
  // The engine's failure is its own (decided first); no ensemble ran on a failed reference.
  const auto& b = c["engines"]["bullet"];
  EXPECT_EQ(b["verdict_kind"], "violates_model");
  EXPECT_FALSE(b["agrees"].get<bool>());
  EXPECT_EQ(b["verdict_decided_by"].get<std::string>().rfind("non_finite at t = ", 0), 0u);
  EXPECT_TRUE(c["predictability"].is_null());
  EXPECT_TRUE(testing_util::AllFinite(c)) << c.dump(2);
  EXPECT_TRUE(testing_util::AllFinite(nlohmann::json::parse(Slurp(dir_ / "summary.json"))));
  EXPECT_TRUE(CsvFinite(dir_ / "comparison.csv"));
}

}  // namespace
}  // namespace rockbench::cli
