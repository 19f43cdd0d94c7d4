// The sweep: its grid, one row per run in a fixed order, results independent of the number of
// threads, and the CSV format.
#include "sweep/sweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/stack_scene.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "tests/common/housner_scene.h"

namespace rockbench {
namespace {

// Housner's block for 0.8 s: the first impact (0.698 s) is inside.
Scene ShortHousner() {
  Scene s = testing_util::HousnerHalfAngleRelease(0.8);
  SetEngineSetting(s, "bullet", "split_impulse_threshold", 0.0);
  return s;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The number of comma-separated fields of a CSV line (no field of these holds a comma).
long Fields(const std::string& line) {
  return std::count(line.begin(), line.end(), ',') + 1;
}

// The CSV with the wall-time column (10th) blanked.
std::string WithoutWallTimes(const std::string& csv) {
  std::string out;
  size_t wall = std::string::npos;
  for (const std::string& line : Lines(csv)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    // The header says which column is wall_s.
    if (wall == std::string::npos) {
      wall = static_cast<size_t>(std::find(f.begin(), f.end(), "wall_s") - f.begin());
    } else if (wall < f.size()) {
      f[wall].clear();
    }
    for (size_t i = 0; i < f.size(); ++i) out += (i ? "," : "") + f[i];
    out += "\n";
  }
  return out;
}

TEST(SweepTest, GridSpansTheRequestedRanges) {
  const std::vector<SweepPoint> full = SweepGrid(false, BuiltEngineNames());
  std::set<double> rtols, rtols_dop853;
  int rk4 = 0;
  size_t engine_points = 0;
  for (const std::string& name : BuiltEngineNames()) {
    engine_points += FindEngine(name)->SweepGrid(false).size();
  }
  for (const SweepPoint& p : full) {
    if (p.engine != "reference") {
      EXPECT_GT(p.setting.time_step_s, 0.0);
      EXPECT_FALSE(p.setting.family.empty());
      EXPECT_FALSE(p.setting.integrator.has_value());
      continue;
    }
    ASSERT_TRUE(p.setting.integrator.has_value());
    const IntegratorSetting& i = *p.setting.integrator;
    if (i.integrator == Integrator::kDopri5) {
      rtols.insert(i.rtol);
      EXPECT_DOUBLE_EQ(i.atol, i.rtol * 1e-2);
    } else if (i.integrator == Integrator::kDop853) {
      rtols_dop853.insert(i.rtol);
      EXPECT_DOUBLE_EQ(i.atol, i.rtol * 1e-2);
    } else {
      ++rk4;
      EXPECT_GT(i.step_s, 0.0);
    }
  }
  EXPECT_DOUBLE_EQ(*rtols.rbegin(), 1e-4);
  EXPECT_DOUBLE_EQ(*rtols.begin(), 1e-12);
  EXPECT_EQ(rk4, 3);
  // dop853 on the full grid only, from rtol 1e-6 to the default.
  EXPECT_EQ(rtols_dop853, (std::set<double>{1e-6, 1e-8, 1e-10, 1e-12}));
  EXPECT_EQ(full.size(), engine_points + rtols.size() + rtols_dop853.size() + 3);
  // Quick is a subset; without engines only reference rows remain, and naming the reference
  // among the engines adds no second set of its points (it stays last).
  EXPECT_LT(SweepGrid(true, BuiltEngineNames()).size(), full.size());
  const std::vector<SweepPoint> alone = SweepGrid(true, {});
  for (const SweepPoint& p : alone) EXPECT_EQ(p.engine, "reference");
  std::vector<std::string> named = BuiltEngineNames();
  named.insert(named.begin(), "reference");
  const std::vector<SweepPoint> with_name = SweepGrid(true, named);
  EXPECT_EQ(with_name.size(), SweepGrid(true, BuiltEngineNames()).size());
  EXPECT_EQ(with_name.back().engine, "reference");
}

TEST(SweepTest, BulletGridSpansItsStepsIterationsAndPrecisions) {
  std::set<double> steps;
  std::set<std::int64_t> iterations;
  std::set<std::string> precisions;
  for (const SweepSetting& p : FindEngine("bullet")->SweepGrid(false)) {
    for (const auto& [key, value] : p.settings) {
      if (key == "time_step") steps.insert(std::get<double>(value));
      if (key == "solver_iterations") iterations.insert(std::get<std::int64_t>(value));
      if (key == "precision") precisions.insert(std::get<std::string>(value));
    }
  }
  EXPECT_DOUBLE_EQ(*steps.rbegin(), 1.0 / 60.0);
  EXPECT_DOUBLE_EQ(*steps.begin(), 1e-5);
  EXPECT_EQ(*iterations.begin(), 4);
  EXPECT_EQ(*iterations.rbegin(), 200);
  EXPECT_EQ(precisions.size(), 2u);
}

TEST(SweepTest, PointSettingsGoIntoTheScene) {
  SweepPoint p;
  p.engine = "bullet";
  p.setting.settings = {{"precision", std::string("float")},
                        {"time_step", 5e-4},
                        {"solver_iterations", std::int64_t{7}}};
  const Scene s = SceneForPoint(ShortHousner(), p);
  const RawEngineTable& t = s.engine_tables.at("bullet");
  EXPECT_EQ(std::get<std::string>(t.values.at("precision").value), "float");
  EXPECT_EQ(std::get<double>(t.values.at("time_step").value), 5e-4);
  EXPECT_EQ(std::get<std::int64_t>(t.values.at("solver_iterations").value), 7);
  // The rest of the scene is kept.
  EXPECT_EQ(std::get<double>(t.values.at("split_impulse_threshold").value), 0.0);
  const SweepPoint r = ReferenceRk4Point(1e-3);
  EXPECT_EQ(SceneForPoint(ShortHousner(), r).model.integrator, Integrator::kRk4);
  EXPECT_EQ(SceneForPoint(ShortHousner(), r).model.step_s, 1e-3);
  // An adaptive point sets its tolerances and keeps the scene's step; it leaves no engine table.
  const Scene d = SceneForPoint(ShortHousner(), ReferenceTolerancePoint(Integrator::kDop853, 1e-6));
  EXPECT_EQ(d.model.integrator, Integrator::kDop853);
  EXPECT_EQ(d.model.rtol, 1e-6);
  EXPECT_EQ(d.model.atol, 1e-8);
  EXPECT_EQ(d.model.step_s, ShortHousner().model.step_s);
  EXPECT_EQ(d.engine_tables.count("reference"), 0u);
}

bool HaveBullet() {
  const std::vector<std::string> e = AvailableEngines();
  return std::find(e.begin(), e.end(), "bullet") != e.end();
}

TEST(SweepTest, RowsAreInGridOrderAndIndependentOfTheThreadCount) {
  const Scene s = ShortHousner();
  const bool bullet = HaveBullet();
  SweepOptions one;
  one.quick = true;
  one.threads = 1;
  int calls = 0, last_done = 0;
  const std::vector<SweepRow> a =
      RunSweep(s, GroundMotion(), one, [&](int done, int total, const SweepPoint&) {
        ++calls;
        EXPECT_EQ(done, last_done + 1);
        last_done = done;
        EXPECT_EQ(total, static_cast<int>(SweepGrid(true, BuiltEngineNames()).size()));
      });
  SweepOptions two = one;
  two.threads = 2;
  two.repeat = 2;
  const std::vector<SweepRow> b = RunSweep(s, GroundMotion(), two);
  const std::vector<SweepPoint> grid = SweepGrid(true, BuiltEngineNames());
  ASSERT_EQ(a.size(), grid.size());
  EXPECT_EQ(calls, static_cast<int>(grid.size()));
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].error.empty()) << a[i].error;
    EXPECT_EQ(a[i].point.engine, grid[i].engine);
    EXPECT_EQ(a[i].point.setting.time_step_s, grid[i].setting.time_step_s);
    EXPECT_GT(a[i].wall_s, 0.0);
  }
  EXPECT_EQ(WithoutWallTimes(SweepCsv(a)), WithoutWallTimes(SweepCsv(b)));
  // Against the tight reference: the reference rows agree far better than Bullet's, and
  // Bullet at 1e-4 s better than at 1/60 s.
  double bullet_fine = 1.0, bullet_coarse = 0.0, reference_worst = 0.0;
  for (const SweepRow& r : a) {
    const double e = r.agreement.angle(1).max_abs_error_rad;
    if (r.point.engine == "reference") reference_worst = std::max(reference_worst, e);
    if (r.point.engine == "bullet" && r.point.setting.family.find("double") != std::string::npos) {
      if (r.point.setting.time_step_s == 1e-4) bullet_fine = std::min(bullet_fine, e);
      if (r.point.setting.time_step_s > 0.01) bullet_coarse = std::max(bullet_coarse, e);
    }
  }
  if (bullet) {
    EXPECT_LT(bullet_fine, bullet_coarse);
    EXPECT_LT(reference_worst, bullet_fine);
  }
  // Every reference setting is within 1e-6 rad of the tight run on this smooth case.
  EXPECT_LT(reference_worst, 1e-6);
}

TEST(SweepTest, CsvHasOneRowPerRunAndAFixedWidth) {
  SweepRow ok;
  ok.point.engine = "bullet";
  ok.point.setting.family = "Bullet double (10 iterations)";
  ok.point.setting.label = "1e-3";
  ok.point.setting.time_step_s = 1e-3;
  ok.point.setting.settings = {{"precision", std::string("double")},
                               {"time_step", 1e-3},
                               {"solver_iterations", std::int64_t{10}}};
  ok.wall_s = 0.5;
  ok.agreement.status = RunStatus::kCompleted;
  ok.agreement.bodies.resize(2);
  SweepRow ref;
  ref.point = ReferenceTolerancePoint(Integrator::kDopri5, 1e-6);
  SweepRow bad;
  bad.point = ReferenceRk4Point(1e-2);
  bad.error = "failed, badly\nsecond line";
  const std::vector<std::string> lines = Lines(SweepCsv({ok, ref, bad}));
  ASSERT_EQ(lines.size(), 4u);
  for (const std::string& l : lines) EXPECT_EQ(Fields(l), Fields(lines[0])) << l;
  EXPECT_EQ(lines[1].rfind("bullet,Bullet double (10 iterations),1e-3,0.001,precision=double;"
                           "solver_iterations=10,,,,,",
                           0),
            0u)
      << lines[1];
  EXPECT_EQ(lines[2].rfind("reference,reference dopri5,1e-6,,,dopri5,1e-06,1e-08,,", 0), 0u)
      << lines[2];
  // An RK4 point shows its step in rk4_step_s, no time step or tolerances.
  EXPECT_EQ(lines[3].rfind("reference,reference RK4,1e-2,,,rk4,,,0.01,error", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find("failed; badly second line"), std::string::npos) << lines[3];
}

TEST(SweepTest, ChosenPointsReplaceTheGrid) {
  SweepOptions o;
  o.points = {ReferenceRk4Point(1e-2), ReferenceRk4Point(5e-3)};
  SweepBaseline baseline;
  const std::vector<SweepRow> rows = RunSweep(ShortHousner(), GroundMotion(), o, {}, &baseline);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].point.setting.integrator->step_s, 1e-2);
  EXPECT_EQ(rows[1].point.setting.integrator->step_s, 5e-3);
  // RK4 is fourth order: halving the step divides the error by about 16 (measured 18).
  const double e0 = rows[0].agreement.angle(1).max_abs_error_rad;
  const double e1 = rows[1].agreement.angle(1).max_abs_error_rad;
  EXPECT_GT(e0 / e1, 8.0);
  // The tight reference: Housner's block released from theta_c / 2 peaks at release.
  EXPECT_GT(baseline.wall_s, 0.0);
  EXPECT_EQ(baseline.status, RunStatus::kCompleted);
  ASSERT_EQ(baseline.blocks(), 1);
  EXPECT_DOUBLE_EQ(baseline.peak_theta_rad[0], ShortHousner().initial.theta_rad[0]);
  EXPECT_EQ(baseline.peak_theta_t_s[0], 0.0);
  EXPECT_EQ(baseline.overturn_block, 0);
}

TEST(SweepTest, JsonSaysWhatTheRowsDoNot) {
  Scene s = ShortHousner();
  s.path = "scenes/housner.toml";
  s.title = "Housner";
  SweepOptions o;
  o.quick = true;
  o.repeat = 3;
  SweepBaseline b;
  b.wall_s = 0.25;
  b.status = RunStatus::kOverturned;
  b.peak_theta_rad = {0.0, 1.5};
  b.peak_theta_t_s = {0.0, 0.0};
  b.overturn_block = 2;
  b.overturn_t_s = 3.5;
  SweepRow failed;
  failed.point.engine = "bullet";
  failed.error = "boom";
  const nlohmann::json j = SweepJson(s, {"run.duration=0.8"}, o, b, {SweepRow{}, failed});
  EXPECT_EQ(j["scene"]["path"], "scenes/housner.toml");
  EXPECT_EQ(j["scene"]["title"], "Housner");
  EXPECT_EQ(j["scene"]["overrides"][0], "run.duration=0.8");
  EXPECT_EQ(j["simulated_duration_s"], 0.8);
  EXPECT_EQ(j["two_blocks"], false);
  EXPECT_EQ(j["options"]["quick"], true);
  EXPECT_EQ(j["options"]["repeat"], 3);
  EXPECT_EQ(j["tight_reference"]["rtol"], kSweepTightRtol);
  EXPECT_EQ(j["tight_reference"]["wall_s"], 0.25);
  EXPECT_EQ(j["tight_reference"]["status"], "overturned");
  EXPECT_EQ(j["tight_reference"]["overturn_block"], 2);
  EXPECT_EQ(j["tight_reference"]["overturn_t_s"], 3.5);
  EXPECT_EQ(j["runs"], 2);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_FALSE(j["machine"].get<std::string>().empty());
  b.overturn_block = 0;
  EXPECT_TRUE(SweepJson(s, {}, o, b, {})["tight_reference"]["overturn_block"].is_null());
  // No dates: the same inputs give the same text.
  EXPECT_EQ(SweepJson(s, {}, o, b, {}).dump(), SweepJson(s, {}, o, b, {}).dump());
}

TEST(SweepTest, RejectsBadOptions) {
  SweepOptions o;
  o.repeat = 0;
  EXPECT_THROW(RunSweep(ShortHousner(), GroundMotion(), o), SceneError);
  o.repeat = 1;
  o.threads = -1;
  EXPECT_THROW(RunSweep(ShortHousner(), GroundMotion(), o), SceneError);
}

// N >= 3 blocks (issue 23): a sweep of a 3-block stack (the reference's points; the engines
// refuse N >= 3 until they are generalised, which is a row's error). Every row compares every
// block, sweep.csv has theta3's five columns after theta2's on every row (an error row too),
// and sweep.json says the stack's blocks and block 3's peak.
TEST(SweepTest, AStackOfThreeBlocksHasEveryBlocksColumns) {
  const Scene s = testing_util::StackScene(3, 0.6);
  SweepOptions o;
  o.threads = 2;
  o.points = {ReferenceRk4Point(1e-2), ReferenceRk4Point(5e-3)};
  SweepBaseline baseline;
  std::vector<SweepRow> rows = RunSweep(s, GroundMotion(), o, {}, &baseline);
  ASSERT_EQ(rows.size(), 2u);
  for (const SweepRow& r : rows) {
    ASSERT_TRUE(r.error.empty()) << r.error;
    ASSERT_EQ(r.agreement.blocks(), 3);
    EXPECT_GT(r.agreement.angle(3).max_abs_error_rad, 0.0);
  }
  // RK4 is fourth order: halving the step divides block 3's error too (by about 16).
  EXPECT_GT(
      rows[0].agreement.angle(3).max_abs_error_rad / rows[1].agreement.angle(3).max_abs_error_rad,
      8.0);
  ASSERT_EQ(baseline.blocks(), 3);
  EXPECT_DOUBLE_EQ(baseline.peak_theta_rad[2], s.initial.theta_rad[2]);
  SweepRow failed;
  failed.point.engine = "bullet";
  failed.error = "engine bullet: N-block scenes (3 blocks) are not simulated yet";
  rows.push_back(failed);
  const std::vector<std::string> lines = Lines(SweepCsv(rows, 3));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_NE(lines[0].find("theta2_peak_time_error_s,theta3_max_abs_error_rad,theta3_rms_error_rad,"
                          "theta3_horizon_s,theta3_peak_rel_error,theta3_peak_time_error_s,"
                          "impacts_reference"),
            std::string::npos)
      << lines[0];
  for (const std::string& line : lines) EXPECT_EQ(Fields(line), Fields(lines[0])) << line;
  // One and two blocks: the columns they always had.
  EXPECT_EQ(Lines(SweepCsv({}, 1))[0], Lines(SweepCsv({}))[0]);
  EXPECT_EQ(Lines(SweepCsv({}))[0].find("theta3"), std::string::npos);
  const nlohmann::json j = SweepJson(s, {}, o, baseline, rows);
  EXPECT_EQ(j["blocks"], 3);
  EXPECT_EQ(j["tight_reference"]["peak_theta3_rad"], s.initial.theta_rad[2]);
}

}  // namespace
}  // namespace rockbench
