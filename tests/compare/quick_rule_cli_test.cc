// compare --quick follows the rule of the full comparison where the reference's model ends
// (issue 38: it said AGREES "over the whole comparison (0.000 s)" where the reference stopped at
// t = 0, where the full comparison says OUTSIDE MODEL). Two stacks whose model ends at a time
// known in closed form: a vertical base acceleration of -1.5 g from start_s leaves the blocks a
// net upward pull of 0.5 g, so every contact force would be tensile from that instant, and the
// linearized equations (without the unilateral model, which runs on the nonlinear ones only)
// stop there. With start_s = 0 the model ends at t = 0; with start_s = 0.5 s, at 0.5 s.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/shell_test.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;
using testing_util::ReadFile;
using testing_util::Rockbench;
using testing_util::ShellRun;

class QuickRule : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rockbench_quick_rule_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    if (Rockbench("engines").output.find("\nbullet:") == std::string::npos) {
      GTEST_SKIP() << "bullet is not built";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A two-block stack tilted 0.01 rad under the vertical pulse from `start`.
  fs::path Scene(const std::string& start) {
    const fs::path p = dir_ / "lift.toml";
    std::ofstream(p) << "[block1]\nwidth = 0.5\nheight = 2.0\ndensity = 2000.0\n"
                        "[block2]\nwidth = 0.4\nheight = 1.0\ndensity = 2000.0\n"
                        "[initial]\ntheta1 = 0.01\n"
                        "[base.vertical]\nkind = \"cosine_pulse\"\namplitude_g = -1.5\n"
                        "frequency_hz = 2.0\nstart_s = "
                     << start
                     << "\n[run]\nduration = 1.0\noutput_interval = 0.01\n"
                        "[model]\nequations = \"linearized\"\n";
    return p;
  }

  // The bullet verdict of `compare` (with --quick or not): its kind, its text and the time the
  // comparison ran to; the printed verdict line must say the same.
  struct Said {
    std::string kind, text;
    double until_s = -1.0;
  };
  Said Compare(const fs::path& scene, bool quick) {
    const fs::path out = dir_ / (quick ? "quick" : "full");
    const ShellRun r = Rockbench("compare " + scene.string() + " --engines bullet --out " +
                                 out.string() + (quick ? " --quick" : ""));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(ReadFile(out / "comparison.json"));
    const nlohmann::json& b = j["engines"]["bullet"];
    Said s{b["verdict_kind"], b["verdict"], b["compared_until_s"]};
    EXPECT_NE(r.output.find("verdict bullet: OUTSIDE MODEL: " + s.text.substr(0, 40)),
              std::string::npos)
        << r.output;
    return s;
  }

  fs::path dir_;
};

TEST_F(QuickRule, AReferenceThatStopsAtTimeZeroIsOutsideTheModelWithAndWithoutQuick) {
  const fs::path scene = Scene("0.0");
  for (const bool quick : {false, true}) {
    const Said s = Compare(scene, quick);
    EXPECT_EQ(s.kind, "outside_model") << (quick ? "--quick: " : "") << s.text;
    EXPECT_NE(s.text.find("the reference's model ends at 0.00 s"), std::string::npos) << s.text;
    EXPECT_EQ(s.text.find("agrees pointwise over the whole comparison"), std::string::npos);
    EXPECT_EQ(s.until_s, 0.0);
  }
}

TEST_F(QuickRule, AReferenceThatStopsAtHalfASecondIsOutsideTheModelWithAndWithoutQuick) {
  const fs::path scene = Scene("0.5");
  for (const bool quick : {false, true}) {
    const Said s = Compare(scene, quick);
    EXPECT_EQ(s.kind, "outside_model") << (quick ? "--quick: " : "") << s.text;
    EXPECT_NE(s.text.find("the reference's model ends at 0.50 s"), std::string::npos) << s.text;
    // The model's end is located to the event tolerance: the pulse's start, 0.5 s.
    EXPECT_NEAR(s.until_s, 0.5, 1e-6);
  }
}

}  // namespace
}  // namespace rockbench
