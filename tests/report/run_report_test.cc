// WriteRunReport on real run folders (made by `rockbench compare` / `rockbench run`): every
// figure comes with its script and data and is on both pages, warnings come first, the energy
// the figure shows is the model's (checked against the reference's own event energies; the
// observables' closed forms are tested in tests/reference/observables_test.cc), the error figure
// reproduces comparison.json, the same folder gives the same bytes, and bad folders are errors
// naming the file.
#include "report/run/run_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/observables.h"
#include "report/common/gnuplot.h"
#include "report/common/interpolation.h"
#include "report/common/page.h"
#include "report/run_folder.h"
#include "scene/history.h"
#include "util/subprocess.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using testing_util::RockbenchOk;
using testing_util::SceneFile;
using testing_util::Slurp;

// Run folders shared by the suite (made once: about 2 s of simulation in all).
class RunReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("rockbench_run_report_test_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    // Two blocks, reference and Bullet, free rocking (no base motion), 2 s.
    // (--engines bullet: every engine's would add the warnings of those that slide, Rapier's.)
    RockbenchOk({"compare", SceneFile("thesis_free_rocking.toml").string(), "--engines", "bullet",
                 "--out", (base_ / "free").string(), "--set", "run.duration=2"});
    // The same with Bullet's friction 0.5 per body (0.25 combined): the model needs 0.7.
    RockbenchOk({"compare", SceneFile("thesis_free_rocking.toml").string(), "--engines", "bullet",
                 "--out", (base_ / "lowmu").string(), "--set", "run.duration=1", "--set",
                 "bullet.friction=0.5"});
    // The reference alone under a harmonic base motion (`rockbench run`).
    RockbenchOk({"run", SceneFile("harmonic.toml").string(), "--out", (base_ / "refonly").string(),
                 "--set", "run.duration=2"});
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  static fs::path base_;
};
fs::path RunReportTest::base_;

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST_F(RunReportTest, EveryFigureHasItsScriptAndDataAndBothPagesShowIt) {
  ASSERT_TRUE(GnuplotAvailable()) << "gnuplot-nox is a test dependency";
  const fs::path out = base_ / "out_figures";
  const RunReportResult r = WriteRunReport(base_ / "free", out);
  EXPECT_EQ(r.name, "free");
  EXPECT_EQ(r.page_dir, out / "free");
  const std::string html = Slurp(r.page_dir / "report.html");
  const std::string md = Slurp(r.page_dir / "report.md");
  // Free rocking: no base-motion figure; the compared engine gives the error figure.
  for (const char* name : {"angles", "angle_error", "impacts", "energy", "friction"}) {
    SCOPED_TRACE(name);
    const fs::path svg = r.page_dir / "figures" / (std::string(name) + ".svg");
    ASSERT_TRUE(fs::is_regular_file(svg));
    EXPECT_GT(fs::file_size(svg), 1000u);
    EXPECT_TRUE(fs::is_regular_file(r.page_dir / "figures" / (std::string(name) + ".gp")));
    bool has_data = false;
    for (const auto& e : fs::directory_iterator(r.page_dir / "figures")) {
      const std::string f = e.path().filename().string();
      has_data = has_data || (f.rfind(std::string(name) + ".", 0) == 0 &&
                              e.path().extension() == ".dat" && fs::file_size(e.path()) > 0);
    }
    EXPECT_TRUE(has_data);
    // The HTML embeds the SVG's bytes; the Markdown links the file.
    EXPECT_NE(html.find("data:image/svg+xml;base64," + Base64(Slurp(svg))), std::string::npos);
    EXPECT_NE(md.find("](figures/" + std::string(name) + ".svg)"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(r.page_dir / "figures" / "base_motion.svg"));
  // Keyframes (peaks and impacts, at most 8) and the animation beside the page.
  int keyframes = 0;
  for (const auto& e : fs::directory_iterator(r.page_dir / "keyframes")) {
    ++keyframes;
    EXPECT_NE(md.find("](keyframes/" + e.path().filename().string() + ")"), std::string::npos);
    EXPECT_NE(html.find("data:image/png;base64," + Base64(Slurp(e.path()))), std::string::npos);
  }
  EXPECT_GE(keyframes, 3);  // the two peaks and at least one impact
  EXPECT_LE(keyframes, 8);
  EXPECT_EQ(r.figure_count, 5 + keyframes);
  EXPECT_EQ(Count(html, "class=\"rb-figure\""), r.figure_count);
  EXPECT_GT(fs::file_size(r.page_dir / "animation.mp4"), 1000u);
  EXPECT_NE(html.find("src=\"animation.mp4\""), std::string::npos);
  EXPECT_TRUE(r.left_out.empty());
  // The metrics table is comparison.json's.
  const auto c = nlohmann::json::parse(Slurp(base_ / "free" / "comparison.json"));
  char max1[32];
  std::snprintf(max1, sizeof max1, "%.3g",
                c["engines"]["bullet"]["theta1"]["max_abs_error_rad"].get<double>());
  EXPECT_NE(md.find(std::string("| bullet | theta1 | ") + max1 + " |"), std::string::npos) << md;
}

TEST_F(RunReportTest, TheKeptScriptRedrawsTheFigureOnItsOwn) {
  ASSERT_TRUE(GnuplotAvailable());
  RunReportOptions o;
  o.keyframes = o.animation = false;
  const RunReportResult r = WriteRunReport(base_ / "free", base_ / "out_redraw", o);
  const fs::path dir = r.page_dir / "figures";
  const std::string first = Slurp(dir / "angles.svg");
  fs::remove(dir / "angles.svg");
  ProcessOptions po;
  po.working_dir = dir;
  po.timeout_s = 60;
  const ProcessResult g = RunProcess({GnuplotProgram(), "angles.gp"}, po);
  ASSERT_TRUE(g.ok()) << g.err;
  EXPECT_EQ(Slurp(dir / "angles.svg"), first);
}

TEST_F(RunReportTest, AReferenceOnlyRunHasNoErrorFigureAndSaysSo) {
  RunReportOptions o;
  o.keyframes = o.animation = false;
  const RunReportResult r = WriteRunReport(base_ / "refonly", base_ / "out_refonly", o);
  const std::string md = Slurp(r.page_dir / "report.md");
  EXPECT_NE(md.find("No engine was compared"), std::string::npos);
  EXPECT_FALSE(fs::exists(r.page_dir / "figures" / "angle_error.svg"));
  // A harmonic base motion: its figure, with the scene's peak (0.4 g) in the caption.
  EXPECT_TRUE(fs::exists(r.page_dir / "figures" / "base_motion.svg"));
  EXPECT_NE(md.find("Horizontal PGA 0.4 g"), std::string::npos) << md;
  EXPECT_EQ(r.figure_count, 5);  // base motion, angles, impacts, energy, friction
  // Parts left out on request are said on the page.
  EXPECT_NE(md.find("left out on request"), std::string::npos);
  EXPECT_FALSE(fs::exists(r.page_dir / "animation.mp4"));
}

// Issue 37: on a scene with a finite friction the reference slides too, so an engine that
// slides is no warning (the slip is compared instead, u1.. in comparison.json); the block that
// slid off its support left it (not "overturned"); the scene table gives each block's friction;
// the tables never break a word. (The infinite-friction case keeps the warning: the next test.)
TEST_F(RunReportTest, AFiniteFrictionSceneSaysTheReferenceSlidesToo) {
  const fs::path run = base_ / "slides_off";
  RockbenchOk({"compare", SceneFile("top_block_slides_off.toml").string(), "--engines", "bullet",
               "--quick", "--out", run.string()});
  RunReportOptions o;
  o.keyframes = o.animation = false;
  const RunReportResult r = WriteRunReport(run, base_ / "out_slides_off", o);
  for (const std::string& w : r.warnings) {
    EXPECT_EQ(w.find("slid"), std::string::npos) << w;
    EXPECT_EQ(w.find("assumes no sliding"), std::string::npos) << w;
    // Past the hand-over the chain's reactions are not the reference's (its unilateral model's
    // normal forces are never negative): no tension is read from them.
    EXPECT_EQ(w.find("Tension"), std::string::npos) << w;
  }
  const std::string md = Slurp(r.page_dir / "report.md");
  EXPECT_EQ(md.find("assumes no sliding"), std::string::npos);
  EXPECT_EQ(md.find("overturned at"), std::string::npos) << md;
  EXPECT_NE(md.find("The reference model: block 2 left its support (slid off it) at t = "),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("bullet: left_support, block 2 left its support"), std::string::npos) << md;
  EXPECT_NE(md.find("friction 0.2 on block 1"), std::string::npos) << md;
  EXPECT_NE(md.find("no sliding on the ground (friction infinite)"), std::string::npos) << md;
  // Block 1 never moves: no relative peak error (its reference peak is ~1e-18 rad).
  EXPECT_NE(md.find("not judged (below the floor)"), std::string::npos) << md;
  EXPECT_NE(md.find("| bullet | u2 (slip) |"), std::string::npos) << md;
  const std::string html = Slurp(r.page_dir / "report.html");
  EXPECT_EQ(html.find("overflow-wrap:anywhere"), std::string::npos);
  EXPECT_NE(html.find("word-break:normal"), std::string::npos);
}

TEST_F(RunReportTest, TooLittleFrictionIsAWarningAtTheTopOfBothPages) {
  RunReportOptions o;
  o.keyframes = o.animation = false;
  const RunReportResult low = WriteRunReport(base_ / "lowmu", base_ / "out_lowmu", o);
  // The model needs about 0.7 at the ground (summary.json friction_required.ground), the scene
  // gives 0.5 * 0.5 = 0.25; Bullet with that friction slides.
  bool ground = false, slid = false;
  for (const std::string& w : low.warnings) {
    ground = ground || w.find("Sliding would occur at the ground") != std::string::npos;
    slid = slid || w.find("The bullet run slid") != std::string::npos;
  }
  EXPECT_TRUE(ground);
  EXPECT_TRUE(slid);
  const std::string html = Slurp(low.page_dir / "report.html");
  const std::string md = Slurp(low.page_dir / "report.md");
  const size_t warn_html = html.find("<div class=\"rb-warnings\"");
  ASSERT_NE(warn_html, std::string::npos);
  EXPECT_LT(warn_html, html.find("<h2>"));
  EXPECT_NE(html.find("Sliding would occur at the ground"), std::string::npos);
  const size_t warn_md = md.find("**Validity warnings**");
  ASSERT_NE(warn_md, std::string::npos);
  EXPECT_LT(warn_md, md.find("\n## "));
  // The same scene with the default friction (3 per body: 9) has nothing to warn about.
  const RunReportResult ok = WriteRunReport(base_ / "free", base_ / "out_lowmu", o);
  EXPECT_TRUE(ok.warnings.empty()) << ok.warnings.front();
  EXPECT_EQ(Slurp(ok.page_dir / "report.html").find("<div class=\"rb-warnings\""),
            std::string::npos);
}

TEST_F(RunReportTest, EnergyFromTheStatesMatchesTheReferenceEventEnergies) {
  const Scene scene = LoadScene(SceneFile("thesis_free_rocking.toml"));
  const reference::Geometry geo = reference::MakeGeometry(scene);
  const History h = ReadHistoryCsv(base_ / "free" / "reference" / "history.csv");
  const std::vector<Event> events = ReadEventsCsv(base_ / "free" / "reference" / "events.csv");
  std::map<double, int> at_time;
  for (const Event& e : events) ++at_time[e.t_s];
  int checked = 0;
  for (const Event& e : events) {
    if (at_time[e.t_s] != 1) continue;  // a cascade: the sample holds the state after them all
    // The history's sample at an event time is the post-event state (the last at that time).
    const Sample* s = nullptr;
    for (const Sample& x : h.samples) {
      if (x.t_s == e.t_s) s = &x;
    }
    ASSERT_NE(s, nullptr) << "no sample at event time " << e.t_s;
    // Angles and rates are written with 13 significant digits: the energy (about 1.8e5 J,
    // smooth in them) agrees to far better than 1e-9 relative.
    EXPECT_NEAR(reference::StateEnergy(geo, reference::StateOf(*s, true)).total_j, e.energy_after_j,
                1e-9 * std::abs(e.energy_after_j))
        << e.kind << " at " << e.t_s;
    ++checked;
  }
  EXPECT_GE(checked, 10);
  // Above rest: zero at rest, positive for the stack released tilted at t = 0.
  EXPECT_DOUBLE_EQ(reference::EnergyAboveRest_j(geo, reference::State{}), 0.0);
  EXPECT_GT(reference::EnergyAboveRest_j(geo, reference::StateOf(h.samples.front(), true)), 0.0);
}

TEST(HistoryInterpolator, ReproducesACubicAndKeepsTheRateJumpOfAnImpact) {
  // theta(t) = t^3 - t on [0, 1] (a cubic: Hermite is exact), then after an "impact" at t = 1
  // the rate jumps from 2 to -1 and theta(t) = -(t - 1) on [1, 2].
  History h;
  h.blocks = 1;
  const auto f = [](double t) { return t <= 1.0 ? t * t * t - t : -(t - 1.0); };
  const auto df = [](double t) { return t < 1.0 ? 3 * t * t - 1.0 : -1.0; };
  for (double t : {0.0, 0.4, 1.0, 1.5, 2.0}) {
    Sample s(1);
    s.t_s = t;
    s.theta_rad[0] = f(t);
    s.omega_radps[0] = df(t);
    h.samples.push_back(s);
  }
  Event impact(1);
  impact.t_s = 1.0;
  impact.kind = "ground_impact";
  impact.omega_before_radps[0] = 2.0;
  impact.omega_after_radps[0] = -1.0;
  const HistoryInterpolator interp(h, {impact});
  for (double t = 0.0; t <= 2.0; t += 0.01) {
    EXPECT_NEAR(interp.Angles(t)[0], f(t), 1e-13) << t;
  }
  EXPECT_EQ(interp.Angles(-1.0)[0], f(0.0));  // clamped
  EXPECT_EQ(interp.Angles(5.0)[0], f(2.0));
}

// Maxima and RMS of the error figure's data file for an engine: (max1, max2, rms1, rms2, n).
std::array<double, 5> ErrorStats(const fs::path& dat_path) {
  std::istringstream dat(Slurp(dat_path));
  std::string line;
  double max1 = 0.0, max2 = 0.0, sum1 = 0.0, sum2 = 0.0;
  int n = 0;
  while (std::getline(dat, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double t, e1, e2;
    ss >> t >> e1 >> e2;
    // Errors below the figure's floor (1e-10 rad) are drawn at it: count them as 0.
    e1 = e1 <= 1e-10 ? 0.0 : e1;
    e2 = e2 <= 1e-10 ? 0.0 : e2;
    max1 = std::max(max1, e1);
    max2 = std::max(max2, e2);
    sum1 += e1 * e1;
    sum2 += e2 * e2;
    ++n;
  }
  return {max1, max2, std::sqrt(sum1 / n), std::sqrt(sum2 / n), static_cast<double>(n)};
}

TEST_F(RunReportTest, TheErrorFigureReproducesComparisonJson) {
  RunReportOptions o;
  o.keyframes = o.animation = false;
  const auto c = nlohmann::json::parse(Slurp(base_ / "free" / "comparison.json"));
  const auto& b = c["engines"]["bullet"];
  const double ref[4] = {b["theta1"]["max_abs_error_rad"].get<double>(),
                         b["theta2"]["max_abs_error_rad"].get<double>(),
                         b["theta1"]["rms_error_rad"].get<double>(),
                         b["theta2"]["rms_error_rad"].get<double>()};
  // comparison.json evaluates the reference's dense output at the engine's sample times; the
  // figure interpolates the stored history there. On the run as written the two share their
  // output grid (5 ms) and agree to 3e-9 relative (the data file's 9 digits; measured).
  const RunReportResult r = WriteRunReport(base_ / "free", base_ / "out_error", o);
  const auto full = ErrorStats(r.page_dir / "figures" / "angle_error.bullet.dat");
  EXPECT_EQ(static_cast<int>(full[4]), b["samples_compared"].get<int>());
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(full[k], ref[k], 1e-6 * ref[k]) << k;

  // With every other regular sample of the reference removed (event samples kept), half of
  // the engine's samples fall between the reference's: the interpolation (cubic Hermite with
  // pre-impact rates) must still give comparison.json's numbers. Measured: within 7.6e-6
  // relative; linear interpolation is 0.7% to 6.5% off, Hermite with the post-impact rates
  // (impacts smeared) 0.5% to 37%. 1e-4 sits between, with a factor 13 to spare.
  const fs::path thin = base_ / "free_thin";
  fs::remove_all(thin);
  fs::copy(base_ / "free", thin, fs::copy_options::recursive);
  History h = ReadHistoryCsv(thin / "reference" / "history.csv");
  std::set<double> event_times;
  for (const Event& e : ReadEventsCsv(thin / "reference" / "events.csv")) event_times.insert(e.t_s);
  History kept = h;
  kept.samples.clear();
  for (size_t i = 0; i < h.samples.size(); ++i) {
    const double t = h.samples[i].t_s;
    const long k = std::lround(t / 0.005);
    const bool regular = std::abs(t - 0.005 * k) < 1e-9;
    if (!regular || event_times.count(t) || k % 2 == 0 || i + 1 == h.samples.size()) {
      kept.samples.push_back(h.samples[i]);
    }
  }
  ASSERT_LT(kept.samples.size(), 0.6 * h.samples.size());
  WriteFileAtomic(thin / "reference" / "history.csv", HistoryToCsv(kept));
  const RunReportResult rt = WriteRunReport(thin, base_ / "out_error", o);
  const auto thinned = ErrorStats(rt.page_dir / "figures" / "angle_error.bullet.dat");
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(thinned[k], ref[k], 1e-4 * ref[k]) << k;
  }
}

TEST_F(RunReportTest, TheSameFolderGivesTheSameBytes) {
  const RunReportResult a = WriteRunReport(base_ / "free", base_ / "same_a");
  const RunReportResult b = WriteRunReport(base_ / "free", base_ / "same_b");
  EXPECT_GT(testing_util::ExpectSameFiles(a.page_dir, b.page_dir), 20);
}

class RunReportErrorTest : public RunReportTest {
 protected:
  // A copy of the free run folder whose summary.json is `summary`.
  fs::path FolderWithSummary(const std::string& name, const std::string& summary) {
    const fs::path dir = base_ / name;
    fs::remove_all(dir);
    fs::copy(base_ / "free", dir, fs::copy_options::recursive);
    WriteFileAtomic(dir / "summary.json", summary);
    return dir;
  }
  std::string ErrorOf(const fs::path& dir) {
    RunReportOptions o;
    o.keyframes = o.animation = false;
    try {
      WriteRunReport(dir, base_ / "out_errors", o);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "no error";
  }
};

TEST_F(RunReportErrorTest, AMissingSceneFileIsNamed) {
  auto s = nlohmann::json::parse(Slurp(base_ / "free" / "summary.json"));
  s["scene"]["path"] = (base_ / "gone" / "scene.toml").string();
  const std::string e = ErrorOf(FolderWithSummary("gone_scene", s.dump()));
  EXPECT_NE(e.find((base_ / "gone" / "scene.toml").string()), std::string::npos) << e;
  EXPECT_NE(e.find("is gone"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(base_ / "out_errors" / "gone_scene" / "report.html"));
}

TEST_F(RunReportErrorTest, AMalformedSummaryIsNamed) {
  const fs::path dir = FolderWithSummary("bad_json", "{\"scene\": {\"path\": ");
  const std::string e = ErrorOf(dir);
  EXPECT_NE(e.find((dir / "summary.json").string()), std::string::npos) << e;
  EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;

  auto s = nlohmann::json::parse(Slurp(base_ / "free" / "summary.json"));
  s["scene"]["path"] = 5;
  const std::string t = ErrorOf(FolderWithSummary("bad_type", s.dump()));
  EXPECT_NE(t.find("summary.json: key 'scene.path' must be a string"), std::string::npos) << t;

  s = nlohmann::json::parse(Slurp(base_ / "free" / "summary.json"));
  s["scene"].erase("path");
  const std::string m = ErrorOf(FolderWithSummary("no_path", s.dump()));
  EXPECT_NE(m.find("summary.json: key 'scene.path' is missing"), std::string::npos) << m;
}

TEST_F(RunReportErrorTest, AMissingOrBrokenHistoryIsNamed) {
  const fs::path dir = FolderWithSummary("no_events", Slurp(base_ / "free" / "summary.json"));
  fs::remove(dir / "bullet" / "events.csv");
  const std::string e = ErrorOf(dir);
  EXPECT_NE(e.find((dir / "bullet" / "events.csv").string()), std::string::npos) << e;

  const fs::path bad = FolderWithSummary("bad_events", Slurp(base_ / "free" / "summary.json"));
  std::string events = Slurp(bad / "reference" / "events.csv");
  events += "1.0,ground_impact,1a,zz,0,0,0,0,0,0,\n";
  WriteFileAtomic(bad / "reference" / "events.csv", events);
  const std::string b = ErrorOf(bad);
  EXPECT_NE(b.find("events.csv:"), std::string::npos) << b;
  EXPECT_NE(b.find("unknown mode 'zz'"), std::string::npos) << b;
}

}  // namespace
}  // namespace rockbench::report
