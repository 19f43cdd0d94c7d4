// The verdict part of a run report, on real `rockbench compare` folders: the Verdict section
// shows each engine's verdict, the reference's convergence, the predictability horizons and the
// statistical tests as comparison.json has them; a reference that is not converged is a warning
// at the top; the angle figure shades the reference ensemble's band and the figures mark the
// horizons only when the folder has them; a --quick folder, or one from a rockbench older than
// the ensembles, still renders and says there is no ensemble; the same folder gives the same
// bytes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "files/atomic_file.h"
#include "report/common/page.h"
#include "report/compare/verdict_section.h"
#include "report/run/run_report.h"
#include "report/run_folder.h"
#include "scene/history.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_util::RockbenchOk;
using testing_util::SceneFile;
using testing_util::Slurp;

class VerdictReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ =
        fs::temp_directory_path() / ("rockbench_verdict_report_test_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    // Two blocks rocking freely for 3 s with the initial state perturbed by 2%: the upper block
    // is predictable for about half the run, the lower one throughout (measured: theta2 horizon
    // 1.67 s, theta1 none), and Bullet's ensemble is compared beyond the horizon. About 3 s.
    RockbenchOk({"compare", SceneFile("thesis_free_rocking.toml").string(), "--out",
                 (base_ / "chaos").string(), "--set", "run.duration=3", "--set",
                 "compare.initial_rel=0.02", "--engine-members", "8", "--jobs", "2", "--engines",
                 "bullet"});
    // The same scene without ensembles.
    RockbenchOk({"compare", SceneFile("thesis_free_rocking.toml").string(), "--out",
                 (base_ / "quick").string(), "--set", "run.duration=1", "--quick", "--engines",
                 "bullet"});
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }

  static RunReportResult Render(const fs::path& run, const std::string& out) {
    RunReportOptions o;
    o.keyframes = o.animation = false;
    return WriteRunReport(run, base_ / out, o);
  }
  // A copy of a run folder to edit.
  static fs::path Copy(const std::string& from, const std::string& to) {
    const fs::path dir = base_ / to;
    fs::remove_all(dir);
    fs::copy(base_ / from, dir, fs::copy_options::recursive);
    return dir;
  }
  static json Comparison(const fs::path& dir) {
    return json::parse(Slurp(dir / "comparison.json"));
  }

  static fs::path base_;
};
fs::path VerdictReportTest::base_;

std::string Fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// The x of every "set arrow from X, graph 0 ..." line of a gnuplot script, by panel (each
// panel starts with "unset arrow"; index 0: before any).
std::vector<std::vector<double>> ArrowTimesByPanel(const std::string& script) {
  std::vector<std::vector<double>> panels(1);
  std::istringstream in(script);
  std::string line;
  while (std::getline(in, line)) {
    if (line == "unset arrow") panels.emplace_back();
    const std::string arrow = "set arrow from ";
    if (line.rfind(arrow, 0) == 0) panels.back().push_back(std::atof(line.c_str() + arrow.size()));
  }
  return panels;
}

// The numbers of every line that is not a comment or a header (CSV or space separated).
std::vector<std::vector<double>> NumberRows(const std::string& text) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream cells(line);
    std::vector<double> row;
    for (double v; cells >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

int CountNear(const std::vector<double>& values, double v) {
  int n = 0;
  for (double x : values) n += std::abs(x - v) < 1e-6 ? 1 : 0;
  return n;
}

// The Markdown table whose header row starts with `first_header`: its body rows.
std::vector<std::string> TableRows(const std::string& md, const std::string& first_header) {
  std::vector<std::string> rows;
  const size_t start = md.find("| " + first_header + " |");
  if (start == std::string::npos) return rows;
  std::istringstream in(md.substr(start));
  std::string line;
  std::getline(in, line);  // header
  std::getline(in, line);  // |---|
  while (std::getline(in, line) && line.rfind("|", 0) == 0) rows.push_back(line);
  return rows;
}

TEST_F(VerdictReportTest, TheVerdictSectionShowsTheVerdictHorizonsAndTests) {
  const json c = Comparison(base_ / "chaos");
  const json& bullet = c["engines"]["bullet"];
  // The folder is what the test needs: one block with a horizon, one without, and statistics.
  ASSERT_TRUE(c["predictability"]["horizon_s"]["theta1"].is_null());
  ASSERT_TRUE(c["predictability"]["horizon_s"]["theta2"].is_number());
  ASSERT_TRUE(bullet["statistics"].is_object() && bullet["statistics"]["available"].get<bool>());

  const RunReportResult r = Render(base_ / "chaos", "out_section");
  const std::string md = Slurp(r.page_dir / "report.md");
  const std::string html = Slurp(r.page_dir / "report.html");
  // Near the top: after the outcome, before the scene.
  const size_t verdict = md.find("\n## Verdict\n");
  ASSERT_NE(verdict, std::string::npos) << md;
  EXPECT_LT(md.find("\n## Outcome\n"), verdict);
  EXPECT_LT(verdict, md.find("\n## Scene\n"));
  // The engine's verdict in comparison.json's own words, and agrees or differs.
  EXPECT_NE(html.find(HtmlEscape(bullet["verdict"].get<std::string>())), std::string::npos);
  const std::vector<std::string> verdicts = TableRows(md, "engine | verdict");
  ASSERT_EQ(verdicts.size(), 1u);
  EXPECT_NE(verdicts[0].find(bullet["agrees"].get<bool>() ? "| AGREES |" : "| DIFFERS |"),
            std::string::npos)
      << verdicts[0];
  EXPECT_NE(md.find("The reference is converged"), std::string::npos);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();

  // The horizons: theta2's value, theta1 predictable for the whole run; the perturbation.
  const double h2 = c["predictability"]["horizon_s"]["theta2"].get<double>();
  const std::vector<std::string> horizons = TableRows(md, "angle | predictability horizon");
  ASSERT_EQ(horizons.size(), 2u);
  EXPECT_NE(horizons[0].find("| theta1 | none |"), std::string::npos) << horizons[0];
  EXPECT_NE(horizons[0].find("predictable for the whole run"), std::string::npos);
  EXPECT_NE(horizons[1].find("| theta2 | " + Fmt("%.6g", h2) + " s |"), std::string::npos)
      << horizons[1];
  const json& p = c["predictability"];
  EXPECT_NE(
      md.find("A reference ensemble of " + std::to_string(p["members"].get<int>()) + " members"),
      std::string::npos);
  EXPECT_NE(
      md.find("(initial_rel " + Fmt("%.4g", p["perturbation"]["initial_rel"].get<double>()) + ")"),
      std::string::npos);
  EXPECT_NE(md.find("seed " + std::to_string(p["perturbation"]["seed"].get<int>())),
            std::string::npos);

  // One row per statistical test, with its medians and Holm-adjusted p from comparison.json.
  const json& tests = bullet["statistics"]["tests"];
  const std::vector<std::string> rows = TableRows(md, "quantity");
  ASSERT_EQ(rows.size(), tests.size()) << md;
  const json& peak2 = tests["peak_theta2_rad"];
  bool found = false;
  for (const std::string& row : rows) {
    if (row.rfind("| peak \\|theta2\\| |", 0) != 0) continue;
    found = true;
    EXPECT_NE(row.find(Fmt("%.4g", peak2["reference"]["median"].get<double>()) + " ["),
              std::string::npos)
        << row;
    EXPECT_NE(row.find(Fmt("%.4g", peak2["engine"]["median"].get<double>()) + " ["),
              std::string::npos)
        << row;
    EXPECT_NE(row.find("| " + Fmt("%.3g", peak2["p_holm"].get<double>()) + " |"), std::string::npos)
        << row;
  }
  EXPECT_TRUE(found) << md;
  int flagged = 0;
  for (const std::string& row : rows) flagged += row.find("| DIFFERS |") != std::string::npos;
  EXPECT_EQ(flagged, static_cast<int>(bullet["statistics"]["rejected"].size()));

  // The pointwise errors split at the horizon.
  const std::vector<std::string> split = TableRows(md, "engine | angle | predictability horizon");
  ASSERT_EQ(split.size(), 2u);
  EXPECT_NE(split[1].find(Fmt("%.3g", bullet["theta2"]["max_abs_error_beyond_rad"].get<double>()) +
                          " rad"),
            std::string::npos)
      << split[1];
  EXPECT_NE(split[0].find("none (predictable throughout)"), std::string::npos) << split[0];
}

TEST_F(VerdictReportTest, AReferenceThatIsNotConvergedIsAWarningInPlainWords) {
  const fs::path dir = Copy("quick", "not_converged");
  json c = Comparison(dir);
  json& conv = c["reference"]["convergence"];
  ASSERT_TRUE(conv.is_object());
  conv["converged"] = false;
  conv["diverges_at_s"] = 0.625;
  conv["max_abs_diff_rad"] = 0.0421;
  conv["used"] = "witness";
  WriteFileAtomic(dir / "comparison.json", c.dump(2));
  const RunReportResult r = Render(dir, "out_not_converged");
  ASSERT_EQ(r.warnings.size(), 1u);
  const std::string& w = r.warnings.front();
  EXPECT_NE(w.find("NOT converged"), std::string::npos) << w;
  EXPECT_NE(w.find("0.0421 rad"), std::string::npos) << w;
  EXPECT_NE(w.find("t = 0.625 s"), std::string::npos) << w;
  EXPECT_NE(w.find("used the witness"), std::string::npos) << w;
  // At the top of the page, and in the Verdict section.
  const std::string html = Slurp(r.page_dir / "report.html");
  const size_t warnings = html.find("<div class=\"rb-warnings\"");
  ASSERT_NE(warnings, std::string::npos);
  EXPECT_LT(warnings, html.find("<h2>"));
  const std::string escaped = HtmlEscape(w);
  EXPECT_NE(html.find(escaped, html.find("<h2>Verdict</h2>")), std::string::npos);

  // The unedited folder is converged: no warning.
  const RunReportResult ok = Render(base_ / "quick", "out_not_converged");
  EXPECT_TRUE(ok.warnings.empty());
  EXPECT_NE(Slurp(ok.page_dir / "report.md").find("The reference is converged"), std::string::npos);
}

TEST_F(VerdictReportTest, TheBandAndTheHorizonsAreDrawnOnlyWhenTheFolderHasThem) {
  const json c = Comparison(base_ / "chaos");
  const double h2 = c["predictability"]["horizon_s"]["theta2"].get<double>();
  const RunReportResult r = Render(base_ / "chaos", "out_band");
  const fs::path figures = r.page_dir / "figures";
  const std::string angles = Slurp(figures / "angles.gp");
  EXPECT_NE(angles.find("filledcurves"), std::string::npos) << angles;
  EXPECT_NE(angles.find("reference ensemble (" +
                        std::to_string(c["predictability"]["members"].get<int>()) + " members)"),
            std::string::npos);
  // The band's data is ensemble_band.csv's (t, then lo and hi of each block) to the axis end.
  const auto csv = NumberRows(Slurp(base_ / "chaos" / "reference" / "ensemble_band.csv"));
  const auto dat = NumberRows(Slurp(figures / "angles.band.dat"));
  ASSERT_FALSE(dat.empty());
  ASSERT_LE(dat.size(), csv.size());
  EXPECT_GE(dat.back()[0], c["engines"]["bullet"]["compared_until_s"].get<double>() - 1e-9);
  for (size_t k = 0; k < dat.size(); ++k) {
    ASSERT_EQ(dat[k].size(), 5u);
    // Columns t, theta1_lo, theta1_hi, theta1_spread, theta1_tol, theta2_lo, theta2_hi, ...
    const double want[5] = {csv[k][0], csv[k][1], csv[k][2], csv[k][5], csv[k][6]};
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(dat[k][i], want[i], 1e-8 * (1 + std::abs(want[i])));
  }
  // The horizon: theta2's panel only on the angle figure (theta1 has none), and on the error
  // figure with the ensemble's spread; both SVGs drawn.
  const auto angle_marks = ArrowTimesByPanel(angles);
  ASSERT_EQ(angle_marks.size(), 3u);  // before the panels, theta1, theta2
  EXPECT_EQ(CountNear(angle_marks[1], h2), 0);
  EXPECT_EQ(CountNear(angle_marks[2], h2), 1);
  const std::string error = Slurp(figures / "angle_error.gp");
  const auto error_marks = ArrowTimesByPanel(error);
  ASSERT_EQ(error_marks.size(), 3u);
  EXPECT_EQ(CountNear(error_marks[2], h2), 1);
  EXPECT_NE(error.find("predictability horizon"), std::string::npos);
  EXPECT_NE(error.find("angle_error.ensemble_spread.dat"), std::string::npos);
  EXPECT_NE(error.find("whole-run tolerance"), std::string::npos);
  // The local tolerance drawn is the one compare judged with: ensemble_band.csv's theta1_tol and
  // theta2_tol columns (written from the harness's profile), to the 9 digits of the figure data.
  EXPECT_NE(error.find("local tolerance"), std::string::npos);
  const auto tol = NumberRows(Slurp(figures / "angle_error.tolerance.dat"));
  ASSERT_GE(tol.size(), csv.size() - 1);
  for (size_t k = 0; k + 1 < csv.size(); ++k) {
    ASSERT_EQ(tol[k].size(), 3u);
    EXPECT_NEAR(tol[k][0], csv[k][0], 1e-9);
    EXPECT_NEAR(tol[k][1], csv[k][4], 1e-8 * csv[k][4]) << "t = " << csv[k][0];
    EXPECT_NEAR(tol[k][2], csv[k][8], 1e-8 * csv[k][8]) << "t = " << csv[k][0];
  }
  EXPECT_NE(Slurp(figures / "angles.svg").find("reference ensemble"), std::string::npos);

  // Without ensemble_band.csv: no band, the horizons still marked.
  const fs::path no_band = Copy("chaos", "no_band");
  fs::remove(no_band / "reference" / "ensemble_band.csv");
  const RunReportResult nb = Render(no_band, "out_band");
  EXPECT_EQ(Slurp(nb.page_dir / "figures" / "angles.gp").find("filledcurves"), std::string::npos);
  EXPECT_FALSE(fs::exists(nb.page_dir / "figures" / "angles.band.dat"));
  EXPECT_EQ(CountNear(ArrowTimesByPanel(Slurp(nb.page_dir / "figures" / "angles.gp"))[2], h2), 1);

  // --quick: no band, no spread, no horizon.
  const RunReportResult q = Render(base_ / "quick", "out_band");
  const std::string quick_angles = Slurp(q.page_dir / "figures" / "angles.gp");
  EXPECT_EQ(quick_angles.find("filledcurves"), std::string::npos);
  EXPECT_EQ(quick_angles.find("predictability horizon"), std::string::npos);
  const std::string quick_error = Slurp(q.page_dir / "figures" / "angle_error.gp");
  EXPECT_EQ(quick_error.find("ensemble_spread"), std::string::npos);
  // The local tolerance is the pointwise check's, drawn with or without an ensemble; the
  // whole-run scale only serves the horizon.
  EXPECT_NE(quick_error.find("local tolerance"), std::string::npos);
  EXPECT_EQ(quick_error.find("whole-run tolerance"), std::string::npos);
}

TEST_F(VerdictReportTest, AFolderWithoutAnEnsembleSaysSoPlainly) {
  const RunReportResult q = Render(base_ / "quick", "out_quick");
  const std::string md = Slurp(q.page_dir / "report.md");
  EXPECT_NE(md.find("No reference ensemble was run"), std::string::npos) << md;
  EXPECT_NE(md.find("no predictability horizon"), std::string::npos);
  EXPECT_NE(md.find("no statistical comparison"), std::string::npos);
  EXPECT_EQ(md.find("### Statistical comparison beyond the horizon"), std::string::npos);
  EXPECT_NE(md.find(Comparison(base_ / "quick")["engines"]["bullet"]["verdict"].get<std::string>()),
            std::string::npos);

  // A folder from a rockbench before verdicts, witnesses and ensembles: none of those keys or
  // files. It renders and says what it does not know.
  const fs::path old = Copy("chaos", "old");
  json c = Comparison(old);
  c.erase("predictability");
  c["reference"].erase("convergence");
  for (const char* k : {"verdict", "verdict_kind", "statistics"}) c["engines"]["bullet"].erase(k);
  WriteFileAtomic(old / "comparison.json", c.dump(2));
  json s = json::parse(Slurp(old / "summary.json"));
  s.erase("convergence");
  WriteFileAtomic(old / "summary.json", s.dump(2));
  for (const char* f :
       {"reference/ensemble_band.csv", "reference/ensemble.csv", "bullet/ensemble.csv"}) {
    fs::remove(old / f);
  }
  const RunReportResult o = Render(old, "out_quick");
  const std::string old_md = Slurp(o.page_dir / "report.md");
  EXPECT_NE(old_md.find("No reference ensemble was run"), std::string::npos);
  EXPECT_NE(old_md.find("No convergence check was recorded"), std::string::npos);
  EXPECT_NE(old_md.find("has no verdict"), std::string::npos);
  EXPECT_EQ(Slurp(o.page_dir / "figures" / "angles.gp").find("filledcurves"), std::string::npos);
}

TEST_F(VerdictReportTest, TheVerdictsWordIsItsKindAndWhatDecidedIt) {
  // Each kind that is not agreement has its own word in the verdict and ranking tables, and the
  // decided-by column carries comparison.json's verdict_decided_by.
  const struct {
    const char* kind;
    const char* label;
  } cases[] = {{"outside_model", "| OUTSIDE MODEL |"},
               {"marginal", "| MARGINAL |"},
               {"violates_model", "| DIFFERS |"}};
  for (const auto& k : cases) {
    const fs::path dir = Copy("chaos", std::string("kind_") + k.kind);
    json c = Comparison(dir);
    json& bullet = c["engines"]["bullet"];
    bullet["verdict_kind"] = k.kind;
    bullet["agrees"] = false;
    bullet["verdict_decided_by"] = std::string("decided by test ") + k.kind;
    WriteFileAtomic(dir / "comparison.json", c.dump(2));
    const RunReportResult r = Render(dir, std::string("out_kind_") + k.kind);
    const std::string md = Slurp(r.page_dir / "report.md");
    const std::vector<std::string> rows = TableRows(md, "engine | verdict");
    ASSERT_EQ(rows.size(), 1u) << k.kind;
    EXPECT_NE(rows[0].find(k.label), std::string::npos) << rows[0];
    EXPECT_NE(rows[0].find(std::string("decided by test ") + k.kind), std::string::npos) << rows[0];
    EXPECT_EQ(rows[0].find("| AGREES |"), std::string::npos) << rows[0];
  }
}

TEST_F(VerdictReportTest, AMalformedBandIsAnInputErrorNamingTheFile) {
  const fs::path dir = Copy("chaos", "bad_band");
  const fs::path csv = dir / "reference" / "ensemble_band.csv";
  std::string text = Slurp(csv);
  text += "3.005,0,zz,0,0,0,0,0,0\n";
  WriteFileAtomic(csv, text);
  try {
    Render(dir, "out_bad_band");
    FAIL() << "no error";
  } catch (const ReportInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(csv.string()), std::string::npos) << what;
    EXPECT_NE(what.find("theta1_hi"), std::string::npos) << what;
  }
}

TEST_F(VerdictReportTest, TheSameFolderGivesTheSameBytes) {
  const RunReportResult a = Render(base_ / "chaos", "same_a");
  const RunReportResult b = Render(base_ / "chaos", "same_b");
  EXPECT_GT(testing_util::ExpectSameFiles(a.page_dir, b.page_dir), 15);
}

// comparison.json engines.<name> with theta2 leaving the tolerance at h2 (NaN: within it for
// the whole 3 s compared), the reference's theta2 horizon hp (NaN: none), and the wall time.
json RankedEngine(bool agrees, double h2, double hp, double wall_s) {
  json e;
  e["agrees"] = agrees;
  e["compared_until_s"] = 3.0;
  e["wall_s"] = wall_s;
  e["theta1"] = {
      {"within_tolerance", true}, {"horizon_s", 3.0}, {"predictability_horizon_s", nullptr}};
  e["theta2"] = {{"within_tolerance", std::isnan(h2)},
                 {"horizon_s", std::isnan(h2) ? 3.0 : h2},
                 {"predictability_horizon_s", std::isnan(hp) ? json(nullptr) : json(hp)}};
  return e;
}

// The ranking: verdict first, then how long an engine stays within the tolerance, but only up to
// the reference's own predictability horizon (a departure beyond it ranks nothing), then cost.
TEST(RankEngines, VerdictThenHorizonCappedAtPredictabilityThenCost) {
  json c;
  const double hp = 1.5;
  c["engines"]["late_but_slow"] = RankedEngine(true, 2.0, hp, 2.0);  // leaves after hp
  c["engines"]["differs"] = RankedEngine(false, 1.0, hp, 0.1);       // cheapest, but differs
  c["engines"]["late_and_fast"] = RankedEngine(true, 2.5, hp, 1.0);  // leaves after hp
  c["engines"]["never_leaves"] = RankedEngine(true, NAN, hp, 5.0);   // within throughout
  const std::vector<std::string> order = {"late_but_slow", "differs", "late_and_fast",
                                          "never_leaves", "not_in_the_file"};
  const std::vector<EngineRank> r = RankEngines(c, order, "comparison.json");
  ASSERT_EQ(r.size(), 4u);
  // All three that agree stay within the tolerance up to the horizon: equal ranked horizons,
  // so the cheaper run ranks first; the one that differs comes last, however cheap.
  EXPECT_EQ(r[0].engine, "late_and_fast");
  EXPECT_EQ(r[1].engine, "late_but_slow");
  EXPECT_EQ(r[2].engine, "never_leaves");
  EXPECT_EQ(r[3].engine, "differs");
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(r[i].ranked_horizon_s, hp) << r[i].engine;
  EXPECT_DOUBLE_EQ(r[3].ranked_horizon_s, 1.0);
  EXPECT_EQ(r[1].first_block, "theta2");
  EXPECT_DOUBLE_EQ(r[1].agreement_horizon_s, 2.0);
  EXPECT_TRUE(r[2].first_block.empty());
  EXPECT_DOUBLE_EQ(r[2].agreement_horizon_s, 3.0);
  EXPECT_DOUBLE_EQ(r[0].wall_per_simulated_s, 1.0 / 3.0);

  // Without a predictability horizon the agreement horizon itself ranks: the engine that stays
  // within the tolerance longer wins although it is slower.
  json d;
  d["engines"]["leaves"] = RankedEngine(true, 2.9, NAN, 0.1);
  d["engines"]["stays"] = RankedEngine(true, NAN, NAN, 9.0);
  const std::vector<EngineRank> q = RankEngines(d, {"leaves", "stays"}, "comparison.json");
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].engine, "stays");
  EXPECT_DOUBLE_EQ(q[1].ranked_horizon_s, 2.9);

  // On the page: a table with one row per engine, in rank order.
  VerdictInput in;
  in.comparison = &c;
  in.comparison_path = "comparison.json";
  in.engines = order;
  in.blocks = 2;
  Page page("t");
  WriteVerdictSection(in, page);
  const std::string md = page.Markdown();
  const std::vector<std::string> rows = TableRows(md, "rank | engine");
  ASSERT_EQ(rows.size(), 4u) << md;
  EXPECT_EQ(rows[0].rfind("| 1 | late_and_fast | AGREES | 2.500 s (theta2) | 1.500 s |", 0), 0u)
      << rows[0];
  EXPECT_EQ(rows[3].rfind("| 4 | differs | DIFFERS |", 0), 0u) << rows[3];

  // A wrongly typed value is an error naming the file and the key.
  c["engines"]["differs"]["wall_s"] = "fast";
  try {
    RankEngines(c, order, "comparison.json");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("comparison.json"), std::string::npos) << what;
    EXPECT_NE(what.find("engines.differs.wall_s"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace rockbench::report
