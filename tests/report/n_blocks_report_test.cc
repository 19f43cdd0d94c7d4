// Reports of N >= 3 blocks (issue 23), on folders made by the real `rockbench` program with the
// reference (the engines refuse N >= 3 until they are generalised): a run page names every
// block's angle, draws one panel per block and one friction curve per interface, its energy is
// the chain's potential energy at the release; a study's page has its table by block; a sweep's
// records and page carry block 3, its figures name every block. An engine's warnings name
// every interface; keyframes of 8 and 10 blocks are fair across the blocks. Keyframes and the
// animation are left out of the pages (renders have their own N-block tests).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/stack_scene.h"
#include "files/atomic_file.h"
#include "files/history_csv.h"
#include "report/common/interpolation.h"
#include "report/run/outcome_section.h"
#include "report/run/pictures_section.h"
#include "report/run/run_report.h"
#include "report/run_folder.h"
#include "report/study/study_report.h"
#include "report/sweep/sweep_csv.h"
#include "report/sweep/work_precision.h"
#include "scene/history.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using testing_util::RockbenchOk;
using testing_util::Slurp;

void WriteText(const fs::path& p, const std::string& text) {
  WriteFileAtomic(p, text);
}

class StackReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("rockbench_n_blocks_report_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    WriteText(base_ / "three.toml", testing_util::StackSceneToml(3, 1.0));
    WriteText(base_ / "six.toml", testing_util::StackSceneToml(6, 0.5));
    // A comparison with the reference alone: its witness, its perturbation members (4).
    RockbenchOk({"compare", (base_ / "three.toml").string(), "--engines", "reference", "--members",
                 "4", "--jobs", "2", "--out", (base_ / "three").string()});
    RockbenchOk({"run", (base_ / "six.toml").string(), "--out", (base_ / "six").string()});
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
  static RunReportOptions Options() {
    RunReportOptions o;
    o.keyframes = false;
    o.animation = false;
    return o;
  }
  static fs::path base_;
};
fs::path StackReportTest::base_;

TEST_F(StackReportTest, ARunPageOfThreeBlocksNamesTheta3) {
  const RunReportResult r = WriteRunReport(base_ / "three", base_ / "out", Options());
  const std::string md = Slurp(r.page_dir / "report.md");
  // The predictability table has a row per block; the scene table a row per block.
  for (const char* text : {"| theta1 |", "| theta2 |", "| theta3 |", "| block 3 (top) |",
                           "| initial state, block 3 |", "| interface3 |"}) {
    EXPECT_NE(md.find(text), std::string::npos) << text;
  }
  // The angles: every block's column, one panel per block.
  const std::string dat = Slurp(r.page_dir / "figures" / "angles.reference.dat");
  EXPECT_EQ(dat.substr(0, dat.find('\n')), "# t_s theta1_rad theta2_rad theta3_rad");
  const std::string gp = Slurp(r.page_dir / "figures" / "angles.gp");
  EXPECT_NE(gp.find("set multiplot layout 3,1"), std::string::npos);
  EXPECT_NE(gp.find("block 3 (top)"), std::string::npos);
  // The band of the 4 members behind every block: t and (lo, hi) of each.
  const std::string band = Slurp(r.page_dir / "figures" / "angles.band.dat");
  EXPECT_EQ(band.substr(0, band.find('\n')),
            "# t_s theta1_lo_rad theta1_hi_rad theta2_lo_rad theta2_hi_rad theta3_lo_rad "
            "theta3_hi_rad");
  // Friction: the ground and both interfaces.
  const std::string friction = Slurp(r.page_dir / "figures" / "friction.dat");
  EXPECT_EQ(friction.substr(0, friction.find('\n')),
            "# t_s mu_ground mu_interface2 mu_interface3 (NaN: normal force below the limit)");
  EXPECT_TRUE(r.left_out.size() >= 1u);  // keyframes and animation, on request
}

// The energy figure of a 6-block run: at the release every block is still, so the energy above
// rest is the potential energy of the tilted chain, computed here independently from the
// pivots' heights (docs/n-blocks.md): with every interface on its right corner, block k's mass
// centre is at y_k = P_k + b_k sin(theta_k) + h_k cos(theta_k) and the next pivot at P_(k+1) =
// P_k - (b_(k+1) - b_k) sin(theta_k) + 2 h_k cos(theta_k). Tolerance: the data file's 9
// significant digits (5e-9 relative) on a sum of six O(100 J) terms.
TEST_F(StackReportTest, TheEnergyOfASixBlockRunIsTheChainsPotentialEnergy) {
  const RunReportResult r = WriteRunReport(base_ / "six", base_ / "out", Options());
  const Scene s = testing_util::StackScene(6, 0.5);
  double pivot = 0.0, rest_base = 0.0, energy = 0.0;
  for (int k = 0; k < 6; ++k) {
    const double b = 0.5 * s.blocks[k].width_m, h = 0.5 * s.blocks[k].height_m;
    const double th = s.initial.theta_rad[k];
    const double y = pivot + b * std::sin(th) + h * std::cos(th);
    energy += s.blocks[k].mass_kg * s.run.gravity_mps2 * (y - (rest_base + h));
    rest_base += 2.0 * h;
    const double b_next = k + 1 < 6 ? 0.5 * s.blocks[k + 1].width_m : b;
    pivot += -(b_next - b) * std::sin(th) + 2.0 * h * std::cos(th);
  }
  std::istringstream dat(Slurp(r.page_dir / "figures" / "energy.reference.dat"));
  std::string header;
  std::getline(dat, header);
  double t = -1.0, e = 0.0;
  dat >> t >> e;
  EXPECT_EQ(t, 0.0);
  EXPECT_NEAR(e, energy, 5e-9 * energy);
  const std::string md = Slurp(r.page_dir / "report.md");
  for (int b = 1; b <= 6; ++b) {
    EXPECT_NE(md.find("| block " + std::to_string(b)), std::string::npos) << b;
  }
  EXPECT_NE(Slurp(r.page_dir / "figures" / "angles.gp").find("set multiplot layout 6,1"),
            std::string::npos);
}

// The interpolator of a 3-block history: every block, at sample times exactly.
TEST_F(StackReportTest, TheInterpolatorHasEveryBlock) {
  const History h = ReadHistoryCsv(base_ / "three" / "reference" / "history.csv");
  ASSERT_EQ(h.blocks, 3);
  const HistoryInterpolator interp(h,
                                   ReadEventsCsv(base_ / "three" / "reference" / "events.csv", 3));
  const Sample& s = h.samples[h.samples.size() / 2];
  const std::vector<double> a = interp.Angles(s.t_s);
  ASSERT_EQ(a.size(), 3u);
  for (int b = 0; b < 3; ++b) EXPECT_EQ(a[b], s.theta_rad[b]) << b;
}

// An engine's warnings on a stack of three blocks name every contact the monitor writes
// (ground, interface2, interface3: engines/common/monitor.cc), not the two-block keys (which a
// three-block summary does not have: their figures would read "nan").
TEST(StackWarnings, AnEnginesWarningsNameEveryInterface) {
  RunData run;
  run.scene = testing_util::StackScene(3, 1.0);
  EngineData ref, engine;
  ref.name = "reference";
  engine.name = "bullet";
  engine.history.blocks = 3;
  engine.summary["status"] = "completed";
  nlohmann::json& v = engine.summary["violations"];
  v["sliding"] = v["uplift"] = v["penetration"] = true;
  v["slip_ground_m"] = 0.001;
  v["slip_interface2_m"] = 0.002;
  v["slip_interface3_m"] = 0.003;
  v["uplift_ground_episodes"] = 0;
  v["uplift_interface3_episodes"] = 2;
  v["uplift_interface3_max_m"] = 0.004;
  v["penetration_ground_max_m"] = 0.0001;
  v["penetration_interface2_max_m"] = 0.005;
  v["penetration_interface3_max_m"] = 0.0002;
  run.engines = {ref, engine};
  std::vector<std::string> warnings;
  EnginesOutcome(run, warnings);
  std::string all;
  for (const std::string& w : warnings) all += w + "\n";
  EXPECT_NE(all.find("slipped 1 mm at the ground, 2 mm at interface 2 (block 2 on block 1) and "
                     "3 mm at interface 3 (block 3 on block 2)."),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("lifted off: 2 time(s) at interface 3 (block 3 on block 2) (up to 4 mm)."),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("sink into each other or the ground by up to 5 mm"), std::string::npos) << all;
  EXPECT_EQ(all.find("nan"), std::string::npos) << all;
}

// A run folder's data made by hand: a stack of `blocks`, the reference's summary (its peaks'
// times, an overturn) and impact events (kind, time).
RunData KeyframeRun(int blocks, const std::vector<double>& peak_t_s, double overturn_t_s,
                    const std::vector<std::pair<std::string, double>>& impacts) {
  RunData run;
  run.scene = testing_util::StackScene(blocks, 2.0);
  EngineData ref;
  ref.name = "reference";
  for (int b = 1; b <= blocks; ++b) {
    ref.summary["peaks"][std::string("theta") + std::to_string(b)]["t_s"] = peak_t_s[b - 1];
  }
  if (overturn_t_s > 0.0) ref.summary["overturn"]["t_s"] = overturn_t_s;
  for (const auto& [kind, t] : impacts) {
    Event e(blocks);
    e.kind = kind;
    e.t_s = t;
    ref.events.push_back(e);
  }
  run.engines.push_back(ref);
  return run;
}

bool HasFrameAt(const std::vector<Keyframe>& frames, double t_s) {
  return std::any_of(frames.begin(), frames.end(),
                     [&](const Keyframe& k) { return std::abs(k.t_s - t_s) < 1e-9; });
}

// Keyframes of 8 and 10 blocks are fair across the blocks. A column released as one peaks
// everywhere at t = 0 (one frame) and its top interface chatters (ten impacts 0.1 s apart)
// before the ground's first impact and interface 3's: in time order the chatter would take
// all 7 frames left; in rounds the ground and interface 3 have theirs. Ten blocks peaking at
// ten different times with an overturn at 2 s: blocks 1 to 8 would take the 8 frames and the
// overturn none; the overturn goes first and the peaks spread from block 1 to block 10.
TEST(StackKeyframes, NoBlocksEventsTakeEveryFrame) {
  std::vector<std::pair<std::string, double>> impacts;
  for (int i = 1; i <= 10; ++i) impacts.push_back({"interface8_impact", 0.1 * i});
  impacts.push_back({"ground_impact", 1.15});
  impacts.push_back({"interface3_impact", 1.35});
  impacts.push_back({"ground_impact", 1.55});
  const std::vector<Keyframe> column =
      KeyframeTimes(KeyframeRun(8, std::vector<double>(8, 0.0), 0.0, impacts), /*max_frames=*/8);
  ASSERT_EQ(column.size(), 8u);
  EXPECT_EQ(column[0].t_s, 0.0);
  EXPECT_EQ(column[0].why.size(), 8u);    // every block's peak in the first frame
  EXPECT_TRUE(HasFrameAt(column, 1.15));  // impact 11: the ground's first
  EXPECT_TRUE(HasFrameAt(column, 1.35));  // impact 12: interface 3's first
  EXPECT_TRUE(HasFrameAt(column, 1.55));  // the ground's second, in round 2
  // The chatter keeps the rest: the first four of interface 8 (rounds 1 to 4).
  for (double t : {0.1, 0.2, 0.3, 0.4}) EXPECT_TRUE(HasFrameAt(column, t)) << t;
  EXPECT_EQ(column[5].Caption(), "impact 11 of the reference");

  std::vector<double> peaks;
  for (int b = 1; b <= 10; ++b) peaks.push_back(0.1 * b);
  const std::vector<Keyframe> tall = KeyframeTimes(KeyframeRun(10, peaks, 2.0, {}), 8);
  ASSERT_EQ(tall.size(), 8u);
  EXPECT_EQ(tall.back().t_s, 2.0);
  EXPECT_EQ(tall.back().Caption(), "overturn (reference)");
  // A frame's text lists its peaks by block, then the overturn (claimed first).
  const std::vector<Keyframe> falls = KeyframeTimes(KeyframeRun(3, {0.0, 0.0, 1.2}, 1.2, {}), 8);
  ASSERT_EQ(falls.size(), 2u);
  EXPECT_EQ(falls[0].Caption(), "peak |theta1| of the reference; peak |theta2| of the reference");
  EXPECT_EQ(falls[1].Caption(), "peak |theta3| of the reference; overturn (reference)");
  // Blocks 1, 3, 4, 6, 7, 9 and 10: i 9 / 6 rounded, i = 0..6, from block 1.
  for (int b : {1, 3, 4, 6, 7, 9, 10}) {
    EXPECT_TRUE(HasFrameAt(tall, 0.1 * b)) << "block " << b;
  }
}

// A study over block3.width (the reference): the page's table by block.
TEST_F(StackReportTest, AStudyPageHasItsTableByBlock) {
  WriteText(base_ / "study.toml",
            "scene = \"three.toml\"\nset = [\"run.duration=0.4\"]\n"
            "[[axis]]\nkey = \"block3.width\"\nvalues = [0.5, 0.8]\n");
  RockbenchOk({"ensemble", (base_ / "study.toml").string(), "--jobs", "1", "--out",
               (base_ / "study").string()});
  const fs::path page = WriteEnsembleReport(base_ / "study", base_ / "out");
  const std::string md = Slurp(page / "report.md");
  EXPECT_NE(md.find("## By block"), std::string::npos) << md;
  for (int b = 1; b <= 3; ++b) {
    EXPECT_NE(md.find("| reference | block " + std::to_string(b) + " | 0 of 2 |"),
              std::string::npos)
        << b << "\n"
        << md;
  }
}

// A sweep of three blocks: its records carry block 3, the largest error is over every block,
// and the page's table has block 3's columns.
TEST_F(StackReportTest, ASweepOfThreeBlocksCarriesBlock3) {
  RockbenchOk({"sweep", (base_ / "three.toml").string(), "--engines", "reference", "--quick",
               "--threads", "2", "--out", (base_ / "sweep").string()});
  const std::vector<SweepRecord> rows =
      ParseSweepCsv(Slurp(base_ / "sweep" / "sweep.csv"), base_ / "sweep" / "sweep.csv");
  ASSERT_FALSE(rows.empty());
  for (const SweepRecord& r : rows) {
    ASSERT_EQ(r.bodies.size(), 3u) << r.line;
    EXPECT_GE(MaxAngleError(r), r.bodies[2].max_abs_error_rad);
    EXPECT_GE(MaxAngleError(r), r.bodies[0].max_abs_error_rad);
  }
  const fs::path page = WriteSweepReport(base_ / "sweep", base_ / "out");
  const std::string md = Slurp(page / "report.md");
  EXPECT_NE(md.find("max err θ3 (largest, rad)"), std::string::npos);
  // The figures' captions and axes name the three blocks, not blocks 1 and 2.
  EXPECT_NE(md.find("|Peak relative error| (the largest of theta1's to theta3's)"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("theta1's and theta2's"), std::string::npos) << md;
  EXPECT_NE(Slurp(page / "figures" / "work_precision.gp").find("max of θ_1 to θ_3 (rad)"),
            std::string::npos);
  EXPECT_NE(Slurp(page / "figures" / "peak_error.gp").find("max of θ_1 to θ_3"), std::string::npos);
}

}  // namespace
}  // namespace rockbench::report
