// The commands downstream of histories on a stack of three blocks (issue 23), as a user runs
// them, with the reference (the engines refuse N >= 3 until they are generalised): compare,
// report, sweep and a study (`rockbench ensemble`) run and write every block's outputs.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "common/stack_scene.h"

namespace {

using rockbench::testing_util::ReadFile;
using rockbench::testing_util::Rockbench;
using rockbench::testing_util::ShellRun;

class StackCliTest : public rockbench::testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    Write("three.toml", rockbench::testing_util::StackSceneToml(3, 0.6));
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(StackCliTest, CompareAndReportOfThreeBlocksWithTheReference) {
  const ShellRun c = Rockbench("compare " + Path("three.toml") +
                               " --engines reference --members 4 --jobs 2 --out " + Path("cmp"));
  ASSERT_EQ(c.exit_code, 0) << c.output;
  // The predictability horizon of every block is printed.
  EXPECT_NE(c.output.find("theta3 horizon"), std::string::npos) << c.output;
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir_ / "cmp" / "comparison.json"));
  EXPECT_EQ(j["scene"]["blocks"], 3);
  EXPECT_TRUE(j["predictability"]["horizon_s"].contains("theta3"));
  EXPECT_TRUE(j["reference"]["convergence"]["max_abs_diff_rad_per_block"]["theta3"].is_number());
  EXPECT_TRUE(j["tolerance"]["theta3_rad"].is_number());
  const std::string band = ReadFile(dir_ / "cmp" / "reference" / "ensemble_band.csv");
  EXPECT_NE(band.substr(0, band.find('\n')).find("theta3_tol"), std::string::npos);
  const ShellRun r = Rockbench("report " + Path("cmp") + " --out " + Path("report") +
                               " --no-keyframes --no-animation");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string md = ReadFile(dir_ / "report" / "cmp" / "report.md");
  EXPECT_NE(md.find("| theta3 |"), std::string::npos) << md;
}

TEST_F(StackCliTest, SweepOfThreeBlocksWithTheReference) {
  const ShellRun s = Rockbench("sweep " + Path("three.toml") +
                               " --engines reference --quick --threads 2 --out " + Path("sweep"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  EXPECT_NE(s.output.find("(0 failed)"), std::string::npos) << s.output;
  const std::string csv = ReadFile(dir_ / "sweep" / "sweep.csv");
  EXPECT_NE(csv.substr(0, csv.find('\n')).find("theta3_max_abs_error_rad"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir_ / "sweep" / "sweep.json"));
  EXPECT_EQ(j["blocks"], 3);
}

TEST_F(StackCliTest, StudyOverBlock3WidthWithTheReference) {
  std::ofstream(dir_ / "study.toml") << "scene = \"three.toml\"\n"
                                        "[[axis]]\nkey = \"block3.width\"\nvalues = [0.5, 0.8]\n";
  const ShellRun e =
      Rockbench("ensemble " + Path("study.toml") + " --jobs 2 --out " + Path("study"));
  ASSERT_EQ(e.exit_code, 0) << e.output;
  const std::string csv = ReadFile(dir_ / "study" / "members.csv");
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_NE(header.find("peak_theta3_rad"), std::string::npos) << header;
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_NE(line.find(",reference,completed,"), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 2);
  EXPECT_EQ(nlohmann::json::parse(ReadFile(dir_ / "study" / "study.json"))["blocks"], 3);
}

}  // namespace
