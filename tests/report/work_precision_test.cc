// The work-precision report of a sweep folder: reading sweep.csv (and its errors), the families
// and labels, the cheapest-setting statement on a synthetic sweep with known numbers, and a real
// quick sweep of Housner's block reported end to end, with the convergence orders it shows.
#include "report/sweep/work_precision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/scratch_dir_test.h"
#include "files/atomic_file.h"
#include "report/common/gnuplot.h"
#include "scene/history.h"
#include "sweep/sweep.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using testing_util::ScratchDirTest;

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A completed two-block row with the numbers that matter to the report.
SweepRow Bullet(const char* precision, double dt, int iterations, double wall_s,
                double max_error_rad, double peak_rel2, bool overturn_agree = true) {
  SweepRow r;
  r.point.engine = "bullet";
  r.point.setting.family =
      std::string("Bullet ") + precision + " (" + std::to_string(iterations) + " iterations)";
  r.point.setting.label = TimeStepLabel(dt);
  r.point.setting.time_step_s = dt;
  r.point.setting.settings = {{"precision", std::string(precision)},
                              {"time_step", dt},
                              {"solver_iterations", std::int64_t{iterations}}};
  r.wall_s = wall_s;
  r.agreement.status = RunStatus::kCompleted;
  r.agreement.bodies.resize(2);
  r.agreement.angle(1).max_abs_error_rad = max_error_rad / 4.0;
  r.agreement.angle(1).peak_rel_error = 1e-4;
  r.agreement.angle(2).max_abs_error_rad = max_error_rad;
  r.agreement.angle(2).peak_rel_error = peak_rel2;
  r.agreement.overturn_agree = overturn_agree;
  return r;
}

SweepRow Dopri(double rtol, double wall_s, double max_error_rad) {
  SweepRow r = Bullet("double", 1.0, 1, wall_s, max_error_rad, 1e-9);
  r.point = ReferenceTolerancePoint(Integrator::kDopri5, rtol);  // atol = rtol / 100
  r.agreement.status = RunStatus::kAtRest;
  return r;
}

SweepRow Rk4(double step_s, double wall_s, double max_error_rad) {
  SweepRow r = Dopri(1.0, wall_s, max_error_rad);
  r.point = ReferenceRk4Point(step_s);
  return r;
}

// The synthetic sweep: the answer is Bullet double (10 iterations), 1e-3 s (0.05 s wall), and
// dopri5 rtol 1e-8 (0.0015 s), 33.3 times cheaper. Cheaper Bullet rows fail one condition each.
std::vector<SweepRow> SyntheticRows() {
  std::vector<SweepRow> rows = {
      Bullet("double", 1e-2, 10, 0.010, 5e-2, -0.05),        // peak 5%: no
      Bullet("double", 1e-3, 10, 0.050, 4e-3, 0.008),        // 0.8%: the answer
      Bullet("double", 1e-4, 10, 0.400, 5e-4, 0.001),        // qualifies, dearer
      Bullet("double", 1e-3, 50, 0.090, 3e-3, -0.005),       // qualifies, dearer
      Bullet("double", 1e-4, 50, 0.800, 4e-4, 0.0005),       // qualifies, dearer
      Bullet("float", 1e-3, 10, 0.030, 5e-3, 0.009, false),  // overturn outcome differs
      Bullet("float", 1e-2, 10, 0.020, 3e-2, 0.005),         // theta1's peak 1.5% (set below)
      Bullet("float", 1.0 / 60.0, 10, 0.004, 9e-2, 0.002),   // non-finite theta2 error (below)
      Bullet("double", 1e-3, 4, 0.001, 1e-3, 0.001),         // failed run (below)
      Dopri(1e-4, 0.0010, 6e-3),  // cheapest reference, but worse than the Bullet run
      Dopri(1e-6, 0.0020, 1e-6),  // good enough, dearer
      Dopri(1e-8, 0.0015, 1e-9),  // the answer
      Dopri(1e-12, 0.0030, 0.0),  // the tight reference's own setting: error 0
      Rk4(1e-3, 0.0040, 1e-11),
  };
  rows[6].agreement.angle(1).peak_rel_error = -0.015;
  rows[7].agreement.angle(2).max_abs_error_rad = NAN;
  rows[8].error = "bullet: the stack blew up";
  return rows;
}

// A sweep folder with sweep.csv and, when `duration_s` > 0, a sweep.json saying so.
fs::path WriteSweepFolder(const fs::path& dir, const std::vector<SweepRow>& rows, double duration_s,
                          double overturn_t_s = 0.0) {
  fs::create_directories(dir);
  WriteFileAtomic(dir / "sweep.csv", SweepCsv(rows));
  if (duration_s > 0.0) {
    Scene scene;
    scene.path = "scenes/synthetic.toml";
    scene.title = "synthetic";
    scene.blocks = {{1.0, 4.0, 1.0, 10000.0, 0.0}};
    scene.blocks.resize(1);
    scene.blocks.push_back(scene.blocks[0]);
    scene.run.duration_s = duration_s;
    SweepBaseline baseline;
    baseline.wall_s = 0.003;
    baseline.status = RunStatus::kAtRest;
    baseline.peak_theta_rad = {0.2, 0.4};  // block 1's: the release angle
    baseline.peak_theta_t_s = {0.0, 1.2};
    if (overturn_t_s > 0.0) {
      baseline.status = RunStatus::kOverturned;
      baseline.overturn_block = 2;
      baseline.overturn_t_s = overturn_t_s;
      baseline.peak_theta_rad[1] = 1.5707963267948966;
      baseline.peak_theta_t_s[1] = overturn_t_s;
    }
    WriteFileAtomic(dir / "sweep.json",
                    SweepJson(scene, {"run.duration=6"}, SweepOptions{}, baseline, rows).dump(2));
  }
  return dir;
}

std::vector<SweepRecord> Parse(const std::vector<SweepRow>& rows) {
  return ParseSweepCsv(SweepCsv(rows), "sweep.csv");
}

TEST(WorkPrecisionTest, ReadsBackWhatTheSweepWrites) {
  const std::vector<SweepRecord> r = Parse(SyntheticRows());
  ASSERT_EQ(r.size(), SyntheticRows().size());
  EXPECT_EQ(r[1].line, 3);
  EXPECT_EQ(r[1].engine, "bullet");
  EXPECT_EQ(r[1].family, "Bullet double (10 iterations)");
  EXPECT_EQ(r[1].setting, "1e-3");
  EXPECT_DOUBLE_EQ(r[1].time_step_s, 1e-3);
  EXPECT_EQ(r[1].settings, "precision=double;solver_iterations=10");
  EXPECT_DOUBLE_EQ(r[1].wall_s, 0.05);
  EXPECT_EQ(r[1].bodies.size(), 2u);
  EXPECT_DOUBLE_EQ(MaxAngleError(r[1]), 4e-3);
  EXPECT_DOUBLE_EQ(MaxPeakRelError(r[1]), 0.008);
  EXPECT_TRUE(r[1].failure.empty());
  EXPECT_FALSE(r[5].overturn_agree);
  EXPECT_NE(r[7].failure.find("non-finite theta2_max_abs_error_rad"), std::string::npos)
      << r[7].failure;
  EXPECT_EQ(r[8].failure, "bullet: the stack blew up");
  EXPECT_EQ(r[9].integrator, "dopri5");
  EXPECT_DOUBLE_EQ(r[9].rtol, 1e-4);
  EXPECT_EQ(r[13].integrator, "rk4");
  EXPECT_DOUBLE_EQ(r[13].rk4_step_s, 1e-3);
  // One block: the theta2 columns are empty.
  SweepRow single = Bullet("double", 1e-3, 10, 0.05, 1e-3, 0.0);
  single.agreement.bodies.resize(1);
  const SweepRecord s = Parse({single})[0];
  EXPECT_EQ(s.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(MaxAngleError(s), 1e-3 / 4.0);
}

TEST(WorkPrecisionTest, ReportNameIsTheSweepFolderName) {
  EXPECT_EQ(SweepReportName("out/sweeps/free"), "free");
  EXPECT_EQ(SweepReportName("out/sweeps/free/"), "free");
  EXPECT_EQ(SweepReportName("out/sweeps/free/."), "free");
  EXPECT_EQ(SweepReportName("/"), "sweep");
  EXPECT_EQ(SweepReportName("."), fs::current_path().filename().string());
}

TEST(WorkPrecisionTest, FamiliesAndLabels) {
  const std::vector<SweepRecord> r = Parse(SyntheticRows());
  EXPECT_EQ(SweepFamily(r[1]), "Bullet double (10 iterations)");
  EXPECT_EQ(SweepFamily(r[5]), "Bullet float (10 iterations)");
  EXPECT_EQ(SweepFamily(r[9]), "reference dopri5");
  EXPECT_EQ(SweepFamily(r[13]), "reference RK4");
  EXPECT_EQ(SweepSettingLabel(r[0]), "1e-2");
  EXPECT_EQ(SweepSettingLabel(r[7]), "1/60");  // the label the sweep wrote for 1/60 s
  EXPECT_EQ(SweepSettingLabel(r[11]), "1e-8");
  EXPECT_EQ(SweepSettingLabel(r[12]), "1e-12");
  EXPECT_EQ(SweepSettingLabel(Parse({Rk4(2.5e-3, 1.0, 1.0)})[0]), "2.5e-3");
  // Families in the fixed order, coarse to fine within each; failed rows left out.
  const auto families = SweepFamilies(r);
  std::vector<std::string> names;
  for (const auto& f : families) names.push_back(f.first);
  const std::vector<std::string> expected = {
      "Bullet double (10 iterations)", "Bullet double (50 iterations)",
      "Bullet float (10 iterations)", "reference dopri5", "reference RK4"};
  EXPECT_EQ(names, expected);
  EXPECT_EQ(families[0].second, (std::vector<size_t>{0, 1, 2}));
  EXPECT_EQ(families[2].second, (std::vector<size_t>{6, 5}));  // row 7 is non-finite
  EXPECT_EQ(families[3].second, (std::vector<size_t>{9, 10, 11, 12}));
}

TEST(WorkPrecisionTest, StatementPicksTheCheapestQualifyingSettings) {
  const std::vector<SweepRecord> r = Parse(SyntheticRows());
  EXPECT_FALSE(ReachesPeakAgreement(r[0], 0.01));  // 5%
  EXPECT_TRUE(ReachesPeakAgreement(r[1], 0.01));
  EXPECT_FALSE(ReachesPeakAgreement(r[5], 0.01));  // overturn outcome
  EXPECT_FALSE(ReachesPeakAgreement(r[6], 0.01));  // theta1 1.5%
  EXPECT_FALSE(ReachesPeakAgreement(r[8], 0.01));  // failed
  const CheapestSetting c = FindCheapestSetting(r);
  ASSERT_TRUE(c.engine_row.has_value());
  EXPECT_EQ(*c.engine_row, 1u);
  ASSERT_TRUE(c.reference.has_value());
  EXPECT_EQ(*c.reference, 11u);
  EXPECT_NE(c.statement.find("Bullet double (10 iterations), time step 1e-3 s, at 0.05 s"),
            std::string::npos)
      << c.statement;
  EXPECT_NE(c.statement.find("reference dopri5, rtol 1e-8 at 0.0015 s"), std::string::npos)
      << c.statement;
  EXPECT_NE(c.statement.find("33.3 times cheaper"), std::string::npos) << c.statement;
  // A 2% criterion admits the float row whose theta1 peak is 1.5% off (0.02 s); its 3e-2 rad
  // error is beaten by dopri5 rtol 1e-4 (6e-3 rad), the cheapest reference row (0.001 s).
  const CheapestSetting loose = FindCheapestSetting(r, 0.02);
  ASSERT_TRUE(loose.engine_row && loose.reference);
  EXPECT_EQ(*loose.engine_row, 6u);
  EXPECT_EQ(*loose.reference, 9u);
}

TEST(WorkPrecisionTest, HistoryCriterionBoundsTheWholeRun) {
  const std::vector<SweepRecord> r = Parse(SyntheticRows());
  // 0.5% of peaks 0.2 and 0.4 rad: 1e-3 and 2e-3 rad. The cheapest Bullet row within both is
  // double, 10 iterations, 1e-4 s (0.4 s; 5e-4 rad); dopri5 rtol 1e-8 beats it at 0.0015 s.
  const AgreementCriterion history = HistoryAgreement(0.005, {0.2, 0.4});
  EXPECT_FALSE(history.reaches(r[1]));  // theta2 4e-3 rad
  EXPECT_TRUE(history.reaches(r[2]));
  EXPECT_FALSE(history.reaches(r[5]));  // overturn outcome
  const CheapestSetting c = FindCheapestSetting(r, history);
  ASSERT_TRUE(c.engine_row && c.reference) << c.statement;
  EXPECT_EQ(*c.engine_row, 2u);
  EXPECT_EQ(*c.reference, 11u);
  EXPECT_NE(c.statement.find("0.5% history agreement (max |angle error| over the whole run <= "
                             "0.5% of the reference's peak angle: 0.001 rad for theta1, 0.002 "
                             "rad for theta2"),
            std::string::npos)
      << c.statement;
  EXPECT_NE(c.statement.find("267 times cheaper"), std::string::npos) << c.statement;
  // One block: theta2 plays no part.
  SweepRow single = Bullet("double", 1e-3, 10, 0.05, 1.0, 0.0);
  single.agreement.bodies.resize(1);
  single.agreement.angle(1).max_abs_error_rad = 1e-3;
  EXPECT_TRUE(HistoryAgreement(0.01, {0.2, 0.0}).reaches(Parse({single})[0]));
  EXPECT_FALSE(HistoryAgreement(0.001, {0.2, 0.0}).reaches(Parse({single})[0]));
}

TEST(WorkPrecisionTest, StatementSaysNoneWhenNothingQualifies) {
  std::vector<SweepRow> rows = SyntheticRows();
  for (SweepRow& row : rows) {
    if (row.point.engine == "bullet" && row.agreement.blocks() >= 2) {
      row.agreement.angle(2).peak_rel_error = 0.02;
    }
  }
  const CheapestSetting none = FindCheapestSetting(Parse(rows));
  EXPECT_FALSE(none.engine_row.has_value());
  EXPECT_FALSE(none.reference.has_value());
  EXPECT_EQ(none.statement.rfind("No bullet setting in this sweep reaches 1%", 0), 0u)
      << none.statement;
  EXPECT_NE(none.statement.find("The most accurate is"), std::string::npos) << none.statement;
  // A Bullet run qualifies but no reference is as accurate.
  rows = SyntheticRows();
  for (SweepRow& row : rows) {
    if (row.point.engine == "reference") row.agreement.angle(2).max_abs_error_rad = 1.0;
  }
  const CheapestSetting no_ref = FindCheapestSetting(Parse(rows));
  ASSERT_TRUE(no_ref.engine_row.has_value());
  EXPECT_FALSE(no_ref.reference.has_value());
  EXPECT_NE(no_ref.statement.find("No reference setting"), std::string::npos) << no_ref.statement;
}

TEST(WorkPrecisionTest, ObservedOrder) {
  // Error 1e-4 at 1e-2, 1e-8 at 1e-3: order 4.
  const SweepRecord coarse = Parse({Rk4(1e-2, 1.0, 1e-4)})[0];
  const SweepRecord fine = Parse({Rk4(1e-3, 1.0, 1e-8)})[0];
  ASSERT_TRUE(ObservedOrder(coarse, fine).has_value());
  EXPECT_NEAR(*ObservedOrder(coarse, fine), 4.0, 1e-5);  // the CSV keeps 7 digits
  EXPECT_FALSE(ObservedOrder(coarse, Parse({Rk4(1e-3, 1.0, 0.0)})[0]).has_value());
}

// A row of engine `name` (its family "<name> ours"), time step dt, theta2's max error err_rad
// (theta1's a quarter of it).
SweepRow EngineRow(const std::string& name, double dt, double wall_s, double err_rad) {
  SweepRow r = Bullet("double", dt, 10, wall_s, err_rad, 1e-4);
  r.point.engine = name;
  r.point.setting.family = name + " ours";
  r.point.setting.settings = {{"time_step", dt}};
  return r;
}

// Equal accuracy: at each level, the cheapest setting of each engine that reaches it, ranked by
// wall time; the fitted order is the slope of log(error) on log(dt).
TEST(WorkPrecisionTest, EnginesRankedByCostAtEachAccuracyLevel) {
  // Peaks 0.2 and 0.4 rad: 10% is 0.02 / 0.04 rad, 1% 2e-3 / 4e-3, 0.1% 2e-4 / 4e-4.
  // Bullet's first family stalls (a coarse solver): the fitted order is that of the family of
  // its most accurate run.
  SweepRow stall_coarse = EngineRow("bullet", 1e-2, 1.0, 5e-2);
  SweepRow stall_fine = EngineRow("bullet", 1e-3, 2.0, 4e-2);
  stall_coarse.point.setting.family = stall_fine.point.setting.family = "bullet coarse solver";
  const std::vector<SweepRecord> r = Parse({
      stall_coarse, stall_fine, EngineRow("bullet", 1e-2, 0.01, 3e-2),  // 10%
      EngineRow("bullet", 1e-3, 0.05, 3e-3),                            // 1%
      EngineRow("bullet", 1e-4, 0.50, 3e-4),                            // 0.1%
      EngineRow("ode", 1e-2, 0.002, 2e-1),                              // none
      EngineRow("ode", 1e-3, 0.02, 2e-3),                               // 1%, cheaper than Bullet's
      EngineRow("ode", 1e-4, 0.20, 1e-3),                               // a floor: not 0.1%
      Dopri(1e-8, 0.0015, 1e-9),  // the reference is not ranked
  });
  std::vector<AgreementCriterion> levels;
  for (double f : {0.1, 0.01, 0.001}) levels.push_back(HistoryAgreement(f, {0.2, 0.4}));
  const std::vector<EngineAtLevels> ranked = RankAtEqualAccuracy(r, levels, 1);
  ASSERT_EQ(ranked.size(), 2u);
  // Sorted by rank at 1%: ODE (0.02 s) before Bullet (0.05 s).
  const EngineAtLevels& ode = ranked[0];
  const EngineAtLevels& bullet = ranked[1];
  ASSERT_EQ(ode.engine, "ode");
  ASSERT_EQ(bullet.engine, "bullet");
  EXPECT_EQ(bullet.cheapest[0], std::optional<size_t>(2));
  EXPECT_EQ(ode.cheapest[0], std::optional<size_t>(6));
  EXPECT_EQ(bullet.rank, (std::vector<int>{1, 2, 1}));
  EXPECT_EQ(ode.rank, (std::vector<int>{2, 1, 0}));
  EXPECT_FALSE(ode.cheapest[2].has_value());
  EXPECT_EQ(ode.most_accurate, std::optional<size_t>(7));
  // Bullet's error falls tenfold per decade of dt: order 1 (the CSV keeps 7 digits).
  ASSERT_TRUE(bullet.order.has_value());
  EXPECT_NEAR(bullet.order->order, 1.0, 1e-5);
  EXPECT_EQ(bullet.order->points, 3);
  EXPECT_DOUBLE_EQ(bullet.order->finest, 1e-4);
  EXPECT_EQ(bullet.order->family, "bullet ours");
  // ODE's: the least-squares slope through log10 errors -0.699, -2.699, -3 at log10 dt -2, -3,
  // -4: 1.1505.
  ASSERT_TRUE(ode.order.has_value());
  EXPECT_NEAR(ode.order->order, 1.1505, 1e-4);
}

class WorkPrecisionFilesTest : public ScratchDirTest {};

TEST_F(WorkPrecisionFilesTest, MalformedCsvNamesFileAndLine) {
  const std::string good = SweepCsv(SyntheticRows());
  auto error_of = [&](const std::string& text) {
    try {
      ParseSweepCsv(text, dir_ / "sweep.csv");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string file = (dir_ / "sweep.csv").string();
  // Line 3 loses a field.
  std::vector<std::string> lines;
  std::istringstream in(good);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  auto join = [](const std::vector<std::string>& ls) {
    std::string t;
    for (const std::string& l : ls) t += l + "\n";
    return t;
  };
  std::vector<std::string> bad = lines;
  bad[2] = bad[2].substr(0, bad[2].rfind(','));
  EXPECT_EQ(error_of(join(bad)).rfind(file + ":3: expected 28 comma-separated fields", 0), 0u)
      << error_of(join(bad));
  // A wall time that is not a number, line 2.
  bad = lines;
  bad[1].replace(bad[1].find(",completed,") + 11, 4, "abc");
  EXPECT_NE(error_of(join(bad)).find(file + ":2: column 'wall_s': expected a number"),
            std::string::npos)
      << error_of(join(bad));
  // No engine on line 4 (any name is read: the sweep may come from a build with other engines),
  // a missing header column, an empty file.
  bad = lines;
  bad[3].replace(0, 6, "");
  EXPECT_NE(error_of(join(bad)).find(":4: column 'engine': expected an engine name or reference"),
            std::string::npos)
      << error_of(join(bad));
  bad = lines;
  bad[0].replace(bad[0].find("wall_s"), 6, "wall");
  EXPECT_NE(error_of(join(bad)).find(":1: header lacks column 'wall_s'"), std::string::npos);
  EXPECT_NE(error_of("").find(":1: empty file"), std::string::npos);
  // A time step that is not positive.
  bad = lines;
  bad[1].replace(bad[1].find(",0.01,"), 6, ",-0.01,");
  EXPECT_NE(error_of(join(bad)).find(":2: column 'time_step_s': expected a positive"),
            std::string::npos)
      << error_of(join(bad));
  // Through the report: the error names the file, and no report is written.
  fs::create_directories(dir_ / "sweep");
  std::ofstream(dir_ / "sweep" / "sweep.csv") << join(bad);
  try {
    WriteSweepReport(dir_ / "sweep", dir_ / "out");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "sweep" / "sweep.csv").string() + ":2:"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "sweep" / "report.html"));
  EXPECT_THROW(WriteSweepReport(dir_ / "nowhere", dir_ / "out"), std::runtime_error);
}

TEST_F(WorkPrecisionFilesTest, ReportOfTheSyntheticSweep) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const fs::path sweep = WriteSweepFolder(dir_ / "free", SyntheticRows(), 6.0);
  const fs::path page = WriteSweepReport(sweep, dir_ / "reports");
  EXPECT_EQ(page, dir_ / "reports" / "free");
  for (const char* f :
       {"report.html", "report.md", "figures/work_precision.svg", "figures/peak_error.svg",
        "figures/work_precision.gp", "figures/work_precision.dat", "figures/peak_error.gp"}) {
    ASSERT_TRUE(fs::exists(page / f)) << f;
    EXPECT_GT(fs::file_size(page / f), 0u) << f;
  }
  // Families and labels in the data and the script; real time at the simulated 6 s.
  const std::string dat = ReadAll(page / "figures/work_precision.dat");
  const std::string gp = ReadAll(page / "figures/work_precision.gp");
  for (const char* family : {"Bullet double (10 iterations)", "Bullet double (50 iterations)",
                             "Bullet float (10 iterations)", "reference dopri5", "reference RK4"}) {
    EXPECT_NE(dat.find(std::string("# ") + family), std::string::npos) << family;
    EXPECT_NE(gp.find(std::string("title \"") + family + "\""), std::string::npos) << family;
  }
  EXPECT_NE(dat.find("0.05 0.004 \"1e-3\""), std::string::npos) << dat;
  EXPECT_NE(dat.find("0.0015 1e-09 \"1e-8\""), std::string::npos) << dat;
  EXPECT_EQ(dat.find("1/60"), std::string::npos);  // the non-finite row is not plotted
  EXPECT_NE(gp.find("set arrow 1 from 6, graph 0 to 6, graph 1"), std::string::npos) << gp;
  EXPECT_NE(gp.find("real time (6 s simulated)"), std::string::npos);
  EXPECT_NE(gp.find("set logscale xy"), std::string::npos);
  EXPECT_NE(gp.find("set xlabel 'wall time of the run (s)'"), std::string::npos);
  // The 1% line on the peak figure.
  EXPECT_NE(ReadAll(page / "figures/peak_error.gp").find("first 0.01 to graph 1, first 0.01"),
            std::string::npos);
  // The page: the statement, the failed runs with their sweep.csv lines, the unplotted zero.
  const std::string md = ReadAll(page / "report.md");
  EXPECT_NE(md.find(FindCheapestSetting(Parse(SyntheticRows())).statement), std::string::npos);
  EXPECT_NE(md.find("2 of 14 runs failed"), std::string::npos);
  EXPECT_NE(md.find("| 9 | Bullet float (10 iterations) | 1/60 | non-finite"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| 10 | Bullet double (4 iterations) | 1e-3 | bullet: the stack blew up |"),
            std::string::npos);
  EXPECT_NE(md.find("Not drawn (zero error, e.g. the tight reference's own setting; no place on "
                    "a log axis): reference dopri5, rtol 1e-12."),
            std::string::npos);
  EXPECT_NE(md.find("simulates 6 s in 0.05 s: 120 times faster than real time"), std::string::npos);
  // theta1 peaks at release: the page says the criterion is blind to it, and adds the history
  // criterion (1% of 0.2 and 0.4 rad).
  EXPECT_NE(md.find("theta1's peak is its release angle"), std::string::npos);
  EXPECT_NE(md.find(FindCheapestSetting(Parse(SyntheticRows()), HistoryAgreement(0.01, {0.2, 0.4}))
                        .statement),
            std::string::npos);
  // The engines at equal accuracy: Bullet's cheapest run within 1% of the peaks over the whole
  // run is 1e-3 s with 10 iterations (theta2 4e-3 rad <= 1% of 0.4 rad), the only engine: #1.
  EXPECT_NE(md.find("#1: 0.05 s (Bullet double (10 iterations), time step 1e-3 s)"),
            std::string::npos)
      << md;
  // Self-contained HTML with both figures embedded.
  const std::string html = ReadAll(page / "report.html");
  size_t figures = 0;
  for (size_t p = html.find("class=\"rb-figure\""); p != std::string::npos;
       p = html.find("class=\"rb-figure\"", p + 1)) {
    ++figures;
  }
  EXPECT_EQ(figures, 2u);
  // Same input, same bytes.
  const std::string svg = ReadAll(page / "figures/work_precision.svg");
  WriteSweepReport(sweep, dir_ / "reports");
  EXPECT_EQ(ReadAll(page / "report.md"), md);
  EXPECT_EQ(ReadAll(page / "figures/work_precision.svg"), svg);
  // When block 2 overturns at 2.5 s, runs stop there: real time is 2.5 s, and the page says
  // that theta2's peak (the overturn angle) tells runs apart by little more than the outcome.
  WriteSweepFolder(sweep, SyntheticRows(), 6.0, 2.5);
  WriteSweepReport(sweep, dir_ / "reports");
  const std::string over_gp = ReadAll(page / "figures/work_precision.gp");
  EXPECT_NE(over_gp.find("set arrow 1 from 2.5, graph 0 to 2.5, graph 1"), std::string::npos);
  EXPECT_NE(over_gp.find("real time (2.5 s simulated: block 2 overturns)"), std::string::npos);
  const std::string over_md = ReadAll(page / "report.md");
  EXPECT_NE(over_md.find("simulates 2.5 s in 0.05 s: 50 times faster"), std::string::npos);
  EXPECT_NE(over_md.find("block 2 overturns, so theta2's peak is the overturn angle"),
            std::string::npos);
  EXPECT_NE(over_md.find("block 2 overturns at 2.5 s"), std::string::npos);
  // Without sweep.json: a warning, no real-time mark.
  fs::remove(sweep / "sweep.json");
  WriteSweepReport(sweep, dir_ / "reports");
  EXPECT_NE(ReadAll(page / "report.md").find("No sweep.json"), std::string::npos);
  EXPECT_EQ(ReadAll(page / "figures/work_precision.gp").find("real time"), std::string::npos);
}

// Housner's block (B = 1 m, H = 4 m) from theta_c / 2 for 0.8 s: one impact at 0.698 s.
Scene ShortHousner() {
  return LoadScene(fs::path(ROCKBENCH_SOURCE_DIR) / "scenes/housner_free_rocking.toml",
                   {"run.duration=0.8"});
}

TEST_F(WorkPrecisionFilesTest, QuickSweepOfHousnerEndToEnd) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const Scene scene = ShortHousner();
  SweepOptions options;
  options.quick = true;
  SweepBaseline baseline;
  const std::vector<SweepRow> rows =
      RunSweep(scene, GroundMotion::FromScene(scene), options, {}, &baseline);
  WriteFileAtomic(dir_ / "housner/sweep.csv", SweepCsv(rows));
  WriteFileAtomic(dir_ / "housner/sweep.json",
                  SweepJson(scene, {"run.duration=0.8"}, options, baseline, rows).dump(2));
  const fs::path page = WriteSweepReport(dir_ / "housner", dir_ / "reports");
  ASSERT_TRUE(fs::exists(page / "figures/work_precision.svg"));
  const std::vector<SweepRecord> r = ParseSweepCsv(ReadAll(dir_ / "housner/sweep.csv"), "x");
  ASSERT_EQ(r.size(), rows.size());
  for (const SweepRecord& x : r) EXPECT_TRUE(x.failure.empty()) << x.line << ": " << x.failure;
  // Every reference setting agrees on the peak and the outcome (errors below 1e-6 rad here).
  const CheapestSetting c = FindCheapestSetting(r);
  const bool bullet =
      std::any_of(r.begin(), r.end(), [](const SweepRecord& x) { return x.engine == "bullet"; });
  for (const SweepRecord& x : r) {
    if (x.engine == "reference") {
      EXPECT_TRUE(ReachesPeakAgreement(x, 0.01)) << x.line;
    }
  }
  if (!bullet) return;
  // Free rocking peaks at the release angle, which every run starts from, so a Bullet setting
  // qualifies; the reference is more accurate than it.
  ASSERT_TRUE(c.engine_row.has_value()) << c.statement;
  ASSERT_TRUE(c.reference.has_value()) << c.statement;
  EXPECT_LT(MaxAngleError(r[*c.reference]), MaxAngleError(r[*c.engine_row]));
  EXPECT_NE(ReadAll(page / "report.md").find(c.statement), std::string::npos);
  // Bullet converges: in double, each family's error falls from 1/60 s to 1e-3 s to 1e-4 s
  // (measured 3.4e-3, 2.0e-4, 2.0e-5 rad for 10 and 50 iterations: first order, a factor 17
  // then 10; any decrease is asserted, the factors depend on where the impact falls in a step).
  for (const auto& [family, indices] : SweepFamilies(r)) {
    if (family.rfind("Bullet double", 0) != 0) continue;
    ASSERT_EQ(indices.size(), 3u) << family;
    for (size_t k = 1; k < indices.size(); ++k) {
      EXPECT_LT(MaxAngleError(r[indices[k]]), MaxAngleError(r[indices[k - 1]]))
          << family << " at " << SweepSettingLabel(r[indices[k]]);
    }
  }
}

TEST_F(WorkPrecisionFilesTest, Rk4HalvingShowsOrderFour) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  // RK4 with located events on Housner's block: halving the step divides the error by 16.
  // Measured: 3.5e-10, 2.0e-11, 1.1e-12 rad at 1e-2, 5e-3, 2.5e-3 s (orders 4.17, 4.10); the
  // next halving reaches the tight reference's own error (~1e-13 rad; order 3.5), so the steps
  // stop at 2.5e-3 s. The band +-0.5 holds the measured orders with room for libm differences.
  const Scene scene = ShortHousner();
  SweepOptions options;
  for (double h : {1e-2, 5e-3, 2.5e-3}) {
    options.points.push_back(ReferenceRk4Point(h));
  }
  const std::vector<SweepRow> rows = RunSweep(scene, GroundMotion::FromScene(scene), options);
  WriteFileAtomic(dir_ / "rk4/sweep.csv", SweepCsv(rows));
  const fs::path page = WriteSweepReport(dir_ / "rk4", dir_ / "reports");
  const std::vector<SweepRecord> r = ParseSweepCsv(ReadAll(dir_ / "rk4/sweep.csv"), "x");
  ASSERT_EQ(r.size(), 3u);
  for (size_t k = 1; k < r.size(); ++k) {
    const std::optional<double> order = ObservedOrder(r[k - 1], r[k]);
    ASSERT_TRUE(order.has_value());
    EXPECT_NEAR(*order, 4.0, 0.5) << "from " << SweepSettingLabel(r[k - 1]) << " to "
                                  << SweepSettingLabel(r[k]);
  }
  // The page's table shows the same orders.
  EXPECT_NE(ReadAll(page / "report.md").find("| reference RK4 | 2.5e-3 |"), std::string::npos);
}

}  // namespace
}  // namespace rockbench::report
