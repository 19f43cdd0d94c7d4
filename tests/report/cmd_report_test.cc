// `rockbench report RUN_DIR... --out DIR` as a program: a page per run folder and an index
// linking them, parts left out on request, and bad input (unknown folder, name clash, bad size,
// a scene file that is gone) exits 2 with a message naming it and writes nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "files/atomic_file.h"
#include "report/run_folder.h"
#include "scene/history.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;
using testing_util::Rockbench;
using testing_util::RockbenchOk;
using testing_util::SceneFile;
using testing_util::Slurp;

class CmdReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("rockbench_cmd_report_test_" + std::to_string(getpid()));
    fs::remove_all(base_);
    // One block with Bullet, and the reference alone under a harmonic: 1 s each.
    RockbenchOk({"compare", SceneFile("housner_free_rocking.toml").string(), "--out",
                 (base_ / "runs" / "housner").string(), "--set", "run.duration=1"});
    RockbenchOk({"run", SceneFile("harmonic.toml").string(), "--out",
                 (base_ / "runs" / "harm").string(), "--set", "run.duration=1"});
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  static fs::path base_;
};
fs::path CmdReportTest::base_;

TEST_F(CmdReportTest, APagePerRunAndAnIndexLinkingThem) {
  const fs::path out = base_ / "out_two";
  RockbenchOk({"report", (base_ / "runs" / "housner").string(), (base_ / "runs" / "harm").string(),
               "--out", out.string(), "--no-animation"});
  for (const char* name : {"housner", "harm"}) {
    EXPECT_TRUE(fs::is_regular_file(out / name / "report.html")) << name;
    EXPECT_TRUE(fs::is_regular_file(out / name / "report.md")) << name;
    EXPECT_TRUE(fs::is_regular_file(out / name / "figures" / "angles.svg")) << name;
  }
  const std::string index_html = Slurp(out / "index.html");
  const std::string index_md = Slurp(out / "index.md");
  EXPECT_NE(index_html.find("href=\"housner/report.html\""), std::string::npos);
  EXPECT_NE(index_html.find("href=\"harm/report.html\""), std::string::npos);
  EXPECT_NE(index_md.find("(housner/report.md)"), std::string::npos);
  EXPECT_NE(index_md.find("(harm/report.md)"), std::string::npos);
  // Only the compared run has an error figure; the page of the other says why.
  EXPECT_TRUE(fs::exists(out / "housner" / "figures" / "angle_error.svg"));
  EXPECT_FALSE(fs::exists(out / "harm" / "figures" / "angle_error.svg"));
  EXPECT_NE(Slurp(out / "harm" / "report.md").find("No engine was compared"), std::string::npos);
  // The compared run's verdict, in comparison.json's words, near the top of its page.
  const auto comparison =
      nlohmann::json::parse(Slurp(base_ / "runs" / "housner" / "comparison.json"));
  const std::string housner_md = Slurp(out / "housner" / "report.md");
  EXPECT_LT(housner_md.find("## Verdict"), housner_md.find("## Scene"));
  EXPECT_NE(housner_md.find(comparison["engines"]["bullet"]["verdict"].get<std::string>()),
            std::string::npos);
  // --no-animation: no video, and the page says it was left out.
  EXPECT_FALSE(fs::exists(out / "housner" / "animation.mp4"));
  EXPECT_NE(Slurp(out / "housner" / "report.md").find("animation: left out on request"),
            std::string::npos);
  EXPECT_TRUE(fs::is_directory(out / "housner" / "keyframes"));
  // No temporary file is left behind.
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
}

TEST_F(CmdReportTest, NoKeyframesAndAnAnimationOfTheAskedSize) {
  const fs::path out = base_ / "out_anim";
  RockbenchOk({"report", (base_ / "runs" / "housner").string(), "--out", out.string(),
               "--no-keyframes", "--animation-size", "320x240", "--fps", "10"});
  EXPECT_FALSE(fs::exists(out / "housner" / "keyframes"));
  EXPECT_NE(Slurp(out / "housner" / "report.md").find("keyframes: left out on request"),
            std::string::npos);
  EXPECT_GT(fs::file_size(out / "housner" / "animation.mp4"), 1000u);
  EXPECT_NE(Slurp(out / "housner" / "report.md").find("10 frames/s, 320x240"), std::string::npos);
}

TEST_F(CmdReportTest, TwoRunsOfOneNameAreAnErrorBeforeAnyWork) {
  fs::create_directories(base_ / "other");
  fs::copy(base_ / "runs" / "harm", base_ / "other" / "harm", fs::copy_options::recursive);
  const fs::path out = base_ / "out_clash";
  const ProcessResult r = Rockbench({"report", (base_ / "runs" / "harm").string(),
                                     (base_ / "other" / "harm").string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the same name 'harm'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "index.html"));
  EXPECT_FALSE(fs::exists(out / "harm"));
}

TEST_F(CmdReportTest, BadInputExits2NamingIt) {
  const fs::path out = base_ / "out_bad";
  // Not a folder.
  ProcessResult r = Rockbench({"report", (base_ / "nowhere").string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find((base_ / "nowhere").string()), std::string::npos) << r.err;
  // A folder that is not a run folder.
  fs::create_directories(base_ / "empty");
  r = Rockbench({"report", (base_ / "empty").string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("neither summary.json"), std::string::npos) << r.err;
  // An odd animation size (H.264 needs even sizes).
  r = Rockbench({"report", (base_ / "runs" / "harm").string(), "--out", out.string(),
                 "--animation-size", "641x360"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--animation-size 641x360"), std::string::npos) << r.err;
  // The scene file the run used is gone.
  fs::create_directories(base_ / "moved");
  fs::copy(base_ / "runs" / "harm", base_ / "moved" / "harm", fs::copy_options::recursive);
  auto s = nlohmann::json::parse(Slurp(base_ / "moved" / "harm" / "summary.json"));
  const std::string gone = (base_ / "moved" / "harmonic.toml").string();
  s["scene"]["path"] = gone;
  WriteFileAtomic(base_ / "moved" / "harm" / "summary.json", s.dump(2));
  r = Rockbench({"report", (base_ / "moved" / "harm").string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the scene file " + gone), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "index.html"));
}

}  // namespace
}  // namespace rockbench
