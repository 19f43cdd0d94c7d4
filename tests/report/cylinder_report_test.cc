// `rockbench report` of a cylinder run folder (docs/report.md "The cylinder"): the page has the
// axis-path figure, whose data are each run's tilt_x and tilt_y columns of history.csv, on equal
// axes, the overturn marked where the reference's path ends and in the direction summary.json
// gives; the tilt figure and the events; the planar stack's sections are left out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "report/run_folder.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;
using testing_util::RockbenchOk;
using testing_util::SceneFile;
using testing_util::Slurp;

// A CSV or whitespace table read as text: its header's names and its rows of numbers.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  size_t Column(const std::string& name) const {
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return i;
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

// history.csv: comma-separated, the last column (mode) text.
Table ReadCsv(const fs::path& path) {
  Table t;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) t.names.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    for (std::string cell; std::getline(row, cell, ',');) {
      values.push_back(cell == "rest" || cell == "rim" ? 0.0 : std::stod(cell));
    }
    t.rows.push_back(values);
  }
  return t;
}

// A figure's .dat: "# name name ..." then rows of numbers (a trailing quoted label ignored).
Table ReadDat(const fs::path& path) {
  Table t;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line.substr(1));
  for (std::string name; header >> name;) t.names.push_back(name);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    for (double v; row >> v;) values.push_back(v);
    t.rows.push_back(values);
  }
  return t;
}

class CylinderReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ =
        fs::temp_directory_path() / ("rockbench_cylinder_report_test_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    // Released beyond its critical angle atan(D/H) = 0.32 rad, its lean turning slowly: it falls
    // toward about azimuth 2.2 (the reference and Bullet).
    std::ofstream(base_ / "fall.toml") << "title = \"A falling cylinder\"\n"
                                          "[[block]]\nshape = \"cylinder\"\ndiameter = 0.5\n"
                                          "height = 1.5\ndensity = 2500.0\n"
                                          "[initial]\ntilt = [0.4]\nazimuth = [2.0]\n"
                                          "azimuth_rate = [0.3]\n"
                                          "[run]\nduration = 3.0\noutput_interval = 0.01\n";
    RockbenchOk({"run", (base_ / "fall.toml").string(), "-e", "reference", "-e", "bullet", "--out",
                 (base_ / "runs" / "fall").string()});
    RockbenchOk({"report", (base_ / "runs" / "fall").string(), "--out", (base_ / "out").string(),
                 "--no-animation"});
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  static fs::path base_;
  static fs::path Page() { return base_ / "out" / "fall"; }
};
fs::path CylinderReportTest::base_;

TEST_F(CylinderReportTest, ThePageShowsTheAxisPathAndTiltFigures) {
  const std::string md = Slurp(Page() / "report.md");
  const std::string html = Slurp(Page() / "report.html");
  for (const char* figure : {"axis_path", "tilt"}) {
    EXPECT_TRUE(fs::is_regular_file(Page() / "figures" / (std::string(figure) + ".svg"))) << figure;
    EXPECT_TRUE(fs::is_regular_file(Page() / "figures" / (std::string(figure) + ".gp"))) << figure;
    EXPECT_NE(md.find("figures/" + std::string(figure) + ".svg"), std::string::npos) << figure;
  }
  EXPECT_NE(md.find("The axis's path seen from above"), std::string::npos);
  EXPECT_FALSE(html.empty());
  // The overturn in words, with its azimuth.
  EXPECT_NE(md.find("the cylinder overturned at t = "), std::string::npos) << md;
  EXPECT_NE(md.find("toward azimuth"), std::string::npos);
  // A keyframe at the reference's peak tilt, drawn in perspective.
  EXPECT_TRUE(fs::is_regular_file(Page() / "keyframes" / "keyframe_01.png"));
  EXPECT_NE(md.find("peak tilt of the reference"), std::string::npos);
  // The planar stack's sections are not there, and the page says why.
  EXPECT_FALSE(fs::exists(Page() / "figures" / "angles.svg"));
  EXPECT_FALSE(fs::exists(Page() / "figures" / "energy.svg"));
  EXPECT_EQ(md.find("## Angles"), std::string::npos);
  EXPECT_NE(md.find("the planar stack's sections"), std::string::npos);
  EXPECT_NE(md.find("## Events"), std::string::npos);
}

TEST_F(CylinderReportTest, TheAxisPathDataAreEachRunsTiltVectorColumns) {
  for (const char* run : {"reference", "bullet"}) {
    const Table history = ReadCsv(base_ / "runs" / "fall" / run / "history.csv");
    const Table dat = ReadDat(Page() / "figures" / ("axis_path." + std::string(run) + ".dat"));
    ASSERT_EQ(dat.names, (std::vector<std::string>{"t_s", "tilt_x1_rad", "tilt_y1_rad"})) << run;
    ASSERT_EQ(dat.rows.size(), history.rows.size()) << run;
    const size_t t = history.Column("t"), tx = history.Column("tilt_x1"),
                 ty = history.Column("tilt_y1");
    for (size_t k = 0; k < dat.rows.size(); ++k) {
      // The data file keeps 9 significant digits: 1e-8 relative, with a floor at 1e-15 rad.
      EXPECT_NEAR(dat.rows[k][0], history.rows[k][t], 1e-8 * std::abs(history.rows[k][t]) + 1e-15);
      EXPECT_NEAR(dat.rows[k][1], history.rows[k][tx],
                  1e-8 * std::abs(history.rows[k][tx]) + 1e-15);
      EXPECT_NEAR(dat.rows[k][2], history.rows[k][ty],
                  1e-8 * std::abs(history.rows[k][ty]) + 1e-15);
    }
  }
}

TEST_F(CylinderReportTest, TheAxesAreEqualAndTheReferencesOverturnIsMarkedWhereItFalls) {
  const std::string gp = Slurp(Page() / "figures" / "axis_path.gp");
  // Equal axes: one unit is as long on both, over the same symmetric range.
  EXPECT_NE(gp.find("set size ratio -1"), std::string::npos);
  const size_t x = gp.find("set xrange ["), y = gp.find("set yrange [");
  ASSERT_NE(x, std::string::npos);
  ASSERT_NE(y, std::string::npos);
  const std::string xr = gp.substr(x + 11, gp.find('\n', x) - x - 11);
  const std::string yr = gp.substr(y + 11, gp.find('\n', y) - y - 11);
  EXPECT_EQ(xr, yr);
  // Each run's curve is plotted from its data file.
  for (const char* run : {"reference", "bullet"}) {
    EXPECT_NE(gp.find("axis_path." + std::string(run) + ".dat"), std::string::npos) << run;
  }
  // The overturn: the reference's point is its path's last point, whose direction is the
  // azimuth summary.json gives for the fall (the columns' definition tilt_x = tilt cos(az),
  // tilt_y = tilt sin(az)), and it is labelled.
  const nlohmann::json summary =
      nlohmann::json::parse(Slurp(base_ / "runs" / "fall" / "summary.json"));
  ASSERT_EQ(summary["status"], "overturned");
  const double azimuth = summary["overturn"]["azimuth_rad"].get<double>();
  const Table marks = ReadDat(Page() / "figures" / "axis_path.overturns.dat");
  ASSERT_EQ(marks.rows.size(), 2u);  // the reference and Bullet both fell
  const Table ref = ReadDat(Page() / "figures" / "axis_path.reference.dat");
  EXPECT_EQ(marks.rows[0][0], ref.rows.back()[1]);
  EXPECT_EQ(marks.rows[0][1], ref.rows.back()[2]);
  // The last sample is the overturn's: the azimuth of the tilt vector is the fall's to the 9
  // digits of the files.
  EXPECT_NEAR(std::atan2(marks.rows[0][1], marks.rows[0][0]), azimuth, 1e-7);
  const std::string overturns = Slurp(Page() / "figures" / "axis_path.overturns.dat");
  EXPECT_NE(overturns.find("reference overturns"), std::string::npos) << overturns;
}

TEST(CylinderReport, ARunThatDoesNotFallHasNoOverturnMark) {
  const fs::path base =
      fs::temp_directory_path() / ("rockbench_cylinder_report_still_" + std::to_string(getpid()));
  fs::remove_all(base);
  RockbenchOk({"run", SceneFile("three_d/cylinder_rotating_harmonic.toml").string(), "--out",
               (base / "runs" / "rot").string(), "--set", "run.duration=1"});
  RockbenchOk({"report", (base / "runs" / "rot").string(), "--out", (base / "out").string(),
               "--no-animation", "--no-keyframes"});
  const fs::path page = base / "out" / "rot";
  EXPECT_TRUE(fs::is_regular_file(page / "figures" / "axis_path.svg"));
  EXPECT_FALSE(fs::exists(page / "figures" / "axis_path.overturns.dat"));
  const std::string md = Slurp(page / "report.md");
  EXPECT_EQ(md.find("overturned"), std::string::npos);
  // Both horizontal components appear in the base motion's figure and table.
  EXPECT_NE(md.find("transverse (+y)"), std::string::npos);
  EXPECT_NE(Slurp(page / "figures" / "base_motion.gp").find("transverse along +y"),
            std::string::npos);
  // The reference tipped from rest (docs/three-d.md: 0.36 g is above the onset (D/H) g = 0.33 g).
  EXPECT_NE(md.find("onsets from rest"), std::string::npos);
  fs::remove_all(base);
}

// A cylinder's compare folder (its ensemble band is of the tilt: tilt1_lo, ...) gets its page,
// with the verdict on tilt_x1 and tilt_y1.
TEST(CylinderReport, ACompareFolderGetsItsPageWithTheVerdict) {
  const fs::path base =
      fs::temp_directory_path() / ("rockbench_cylinder_report_compare_" + std::to_string(getpid()));
  fs::remove_all(base);
  RockbenchOk({"compare", SceneFile("three_d/cylinder_rotating_harmonic.toml").string(), "--out",
               (base / "runs" / "cmp").string(), "--engines", "ode", "--members", "6",
               "--engine-members", "0", "--set", "run.duration=2"});
  ASSERT_NE(Slurp(base / "runs" / "cmp" / "reference" / "ensemble_band.csv").find("t,tilt1_lo,"),
            std::string::npos);
  RockbenchOk({"report", (base / "runs" / "cmp").string(), "--out", (base / "out").string(),
               "--no-animation", "--no-keyframes"});
  const std::string md = Slurp(base / "out" / "cmp" / "report.md");
  EXPECT_NE(md.find("Verdict"), std::string::npos);
  EXPECT_NE(md.find("tilt_x1"), std::string::npos);
  fs::remove_all(base);
}

}  // namespace
}  // namespace rockbench
