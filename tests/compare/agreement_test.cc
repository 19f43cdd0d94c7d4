// The comparison with the reference: errors on the engine's grid with the reference's dense
// output, horizon, RMS, peaks, impact sequence matching, overturning, final state, and the
// comparison.json / comparison.csv formats.
#include "compare/agreement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "tests/common/housner_scene.h"
#include "tests/common/initial_state.h"
#include "tests/common/reference_suite.h"

namespace rockbench {
namespace {

// Housner's block released from theta_c / 2 (4 s, four impacts in the reference).
Scene Housner() {
  return testing_util::HousnerHalfAngleRelease(4.0);
}

// An "engine" that reports the reference's own trajectory plus err(t), on its own grid.
EngineRun FromReference(const reference::Result& ref, double t0, double dt, double t_end,
                        double (*err)(double)) {
  EngineRun run;
  run.engine = "fake";
  run.history.blocks = 1;
  for (double t = t0; t <= t_end + 1e-12; t += dt) {
    Sample s = ref.trajectory.At(t);
    s.t_s = t;
    s.theta_rad[0] += err(t);
    run.history.samples.push_back(s);
  }
  run.history.events = ref.history.events;
  run.summary = nlohmann::json::object();
  // The outcome a monitor would report: the peak over the samples.
  run.outcome = RunOutcome(1);
  run.outcome.status = RunStatus::kCompleted;
  for (const Sample& x : run.history.samples) {
    if (std::abs(x.theta_rad[0]) > run.outcome.peak_theta_rad[0]) {
      run.outcome.peak_theta_rad[0] = std::abs(x.theta_rad[0]);
      run.outcome.peak_theta_t_s[0] = x.t_s;
    }
  }
  run.wall_s = 0.5;
  return run;
}

class CompareTest : public testing_util::ReferenceSuite<CompareTest> {
 protected:
  static void SetUpTestSuite() { RunReference(Housner()); }
};

TEST_F(CompareTest, InterpolatesTheReferenceAtTheEngineTimesNotTheNearestSample) {
  // Engine samples 3.7 ms off the reference's 10 ms grid, exact values: no error at all. A
  // nearest-sample comparison would see |omega| * 3.7 ms, up to 1.5e-3 rad.
  const EngineRun run = FromReference(*ref_, 0.0037, 0.01, 3.99, [](double) { return 0.0; });
  const EngineAgreement a = CompareWithReference(*scene_, *ref_, run);
  EXPECT_LT(a.angle(1).max_abs_error_rad, 1e-12);
  EXPECT_EQ(a.blocks(), 1);
  EXPECT_TRUE(a.angle(1).within_tolerance);
  EXPECT_EQ(a.samples_compared, static_cast<int>(run.history.samples.size()));
}

TEST_F(CompareTest, ErrorMetricsAndHorizon) {
  // err = 2e-3 sin(2 pi t / 4): max 2e-3, RMS 2e-3 / sqrt(2) over whole periods on a fine grid.
  // Tolerance 1e-3 rad: first exceeded where sin = 1/2, t = 4/12 = 0.3333 s.
  Scene s = *scene_;
  s.compare.tolerance_rad = 1e-3;
  const EngineRun run = FromReference(*ref_, 0.0, 1e-3, 4.0, [](double t) {
    return 2e-3 * std::sin(2.0 * std::numbers::pi * t / 4.0);
  });
  const EngineAgreement a = CompareWithReference(s, *ref_, run);
  EXPECT_NEAR(a.angle(1).max_abs_error_rad, 2e-3, 1e-9);
  EXPECT_NEAR(a.angle(1).rms_error_rad, 2e-3 / std::sqrt(2.0), 2e-6);
  EXPECT_FALSE(a.angle(1).within_tolerance);
  EXPECT_NEAR(a.angle(1).horizon_s, 1.0 / 3.0, 1e-3);
  EXPECT_LE(a.angle(1).max_abs_error_horizon_rad, 1e-3);
  EXPECT_NEAR(a.angle(1).max_abs_error_horizon_rad, 1e-3, 1e-5);
  EXPECT_DOUBLE_EQ(a.angle(1).tolerance_rad, 1e-3);
  // Default tolerance: 10% of the reference's peak |theta1| (the release angle here).
  const EngineAgreement d = CompareWithReference(*scene_, *ref_, run);
  EXPECT_DOUBLE_EQ(d.angle(1).tolerance_rad, 0.1 * ref_->summary.peak_theta_rad[0]);
  EXPECT_TRUE(d.angle(1).within_tolerance);
  EXPECT_NEAR(d.angle(1).horizon_s, 4.0, 1e-9);  // the end of the grid
}

TEST_F(CompareTest, PeaksAreTheOnesTheEngineMeasured) {
  // An engine measures its peaks at every step (its outcome), not at the output samples.
  EngineRun run = FromReference(*ref_, 0.0, 0.01, 4.0, [](double) { return 0.0; });
  EngineAgreement a = CompareWithReference(*scene_, *ref_, run);
  // The release at t = 0 is the peak here.
  EXPECT_NEAR(a.angle(1).peak_rel_error, 0.0, 1e-12);
  EXPECT_NEAR(a.angle(1).peak_time_error_s, 0.0, 1e-12);
  run.outcome.peak_theta_rad[0] = 1.01 * ref_->summary.peak_theta_rad[0];
  run.outcome.peak_theta_t_s[0] = ref_->summary.peak_theta_t_s[0] + 0.02;
  a = CompareWithReference(*scene_, *ref_, run);
  EXPECT_NEAR(a.angle(1).peak_rel_error, 0.01, 1e-12);
  EXPECT_NEAR(a.angle(1).peak_time_error_s, 0.02, 1e-12);
}

Event Impact(double t, const char* kind, double w1 = -0.4, double w2 = 0.0) {
  Event e(2);
  e.t_s = t;
  e.kind = kind;
  e.omega_before_radps[0] = w1;
  e.omega_before_radps[1] = w2;
  return e;
}

TEST_F(CompareTest, MatchesImpactsUntilTheFirstMissingOrExtraOne) {
  reference::Result ref = *ref_;
  ref.history.events = {Impact(0.7, "ground_impact"), Impact(1.8, "ground_impact"),
                        Impact(2.0, "interface_impact", 0.0, 0.5), Impact(2.8, "ground_impact"),
                        Impact(3.0, "ground_impact", 0.001)};
  EngineRun run = FromReference(ref, 0.0, 0.01, 4.0, [](double) { return 0.0; });
  // Same sequence, shifted by +1, -2, +3, -4 ms; the last (0.001 rad/s) is too slow to count.
  run.history.events = {Impact(0.701, "ground_impact"), Impact(1.798, "ground_impact"),
                        Impact(2.003, "interface_impact", 0.0, 0.5),
                        Impact(2.796, "ground_impact")};
  EngineAgreement a = CompareWithReference(*scene_, ref, run);
  EXPECT_EQ(a.impacts.reference_impacts, 4);
  EXPECT_EQ(a.impacts.reference_impacts_all, 5);
  EXPECT_EQ(a.impacts.matched, 4);
  ASSERT_EQ(a.impacts.time_errors_s.size(), 4u);
  EXPECT_NEAR(a.impacts.time_errors_s[1], -0.002, 1e-12);
  EXPECT_NEAR(a.impacts.max_abs_time_error_s, 0.004, 1e-12);
  EXPECT_TRUE(a.impacts.first_mismatch.empty()) << a.impacts.first_mismatch;
  // An extra engine impact between the first two stops the matching there.
  run.history.events.insert(run.history.events.begin() + 1, Impact(1.2, "ground_impact"));
  a = CompareWithReference(*scene_, ref, run);
  EXPECT_EQ(a.impacts.matched, 1);
  EXPECT_EQ(a.impacts.first_mismatch, "extra ground_impact at 1.200000 s");
  // A missing one (the interface impact) too; a wrong kind counts as a mismatch.
  run.history.events = {Impact(0.701, "ground_impact"), Impact(1.798, "ground_impact"),
                        Impact(2.796, "ground_impact")};
  a = CompareWithReference(*scene_, ref, run);
  EXPECT_EQ(a.impacts.matched, 2);
  EXPECT_EQ(a.impacts.first_mismatch, "missing interface_impact at 2.000000 s");
}

TEST_F(CompareTest, OverturningAndFinalState) {
  EngineRun run = FromReference(*ref_, 0.0, 0.01, 4.0, [](double) { return 0.0; });
  EngineAgreement a = CompareWithReference(*scene_, *ref_, run);
  EXPECT_TRUE(a.overturn_agree);
  EXPECT_TRUE(a.final_agree);
  EXPECT_EQ(a.final_mode_reference, "rocking");
  // The engine says block 1 overturned; the reference did not.
  run.outcome.overturned_block = 1;
  run.outcome.overturn_t_s = 3.0;
  a = CompareWithReference(*scene_, *ref_, run);
  EXPECT_FALSE(a.overturn_agree);
  EXPECT_FALSE(a.final_agree);
  EXPECT_EQ(a.final_mode_engine, "overturned");
  // An engine at rest at the end while the reference still rocks.
  run = FromReference(*ref_, 0.0, 0.01, 4.0, [](double) { return 0.0; });
  run.history.samples.back().mode = Configuration(1);
  a = CompareWithReference(*scene_, *ref_, run);
  EXPECT_FALSE(a.final_agree);
}

TEST_F(CompareTest, JsonAndCsvCarryTheKeysOtherToolsRead) {
  Scene two;
  two.blocks = {BlockDef{1.25, 1.25, 1.0, 3906.25, 0.0}, BlockDef{1.0, 2.5, 1.0, 6250.0, 0.0}};
  two.initial = testing_util::Initial(0.15, 0.15, 0.0, 0.0);
  two.run.duration_s = 1.0;
  const reference::Result ref = reference::Simulate(two, GroundMotion());
  EngineRun run;
  run.engine = "bullet";
  run.history.blocks = 2;
  for (double t = 0.0; t <= 1.0; t += 0.01) {
    Sample x = ref.trajectory.At(t);
    x.theta_rad[1] += 1e-3;
    run.history.samples.push_back(x);
  }
  run.wall_s = 0.25;
  const EngineAgreement a = CompareWithReference(two, ref, run);
  ASSERT_EQ(a.blocks(), 2);
  EXPECT_NEAR(a.angle(2).max_abs_error_rad, 1e-3, 1e-9);
  const nlohmann::json j = ComparisonJson(two, ref, 0.01, {a});
  const nlohmann::json& e = j["engines"]["bullet"];
  EXPECT_EQ(e["wall_s"], 0.25);
  EXPECT_TRUE(e.contains("impacts_matched"));
  for (const char* b : {"theta1", "theta2"}) {
    for (const char* k : {"max_abs_error_rad", "rms_error_rad", "peak_rel_error",
                          "peak_time_error_s", "horizon_s"}) {
      EXPECT_TRUE(e[b].contains(k)) << b << "." << k;
      EXPECT_TRUE(e[b][k].is_number()) << b << "." << k;
    }
  }
  EXPECT_EQ(j["reference"]["status"], StatusText(ref.summary.status));
  // CSV: a header and one row per block, same number of fields.
  const std::string csv = ComparisonCsv({a});
  std::istringstream in(csv);
  std::string header, row1, row2, extra;
  std::getline(in, header);
  std::getline(in, row1);
  std::getline(in, row2);
  EXPECT_FALSE(std::getline(in, extra));
  auto fields = [](const std::string& s) { return std::count(s.begin(), s.end(), ',') + 1; };
  EXPECT_EQ(fields(row1), fields(header));
  EXPECT_EQ(fields(row2), fields(header));
  EXPECT_EQ(row1.rfind("bullet,1,", 0), 0u);
  EXPECT_EQ(row2.rfind("bullet,2,", 0), 0u);
}

TEST(CompareTolerance, ABlockThatNeverMovesIsNotHeldToAToleranceOfZero) {
  // Block 2 (0.4 x 1.2 m) rocks on a wide, squat block 1 (3 x 0.5 m) that never lifts: the
  // reference's peak theta1 is 0, so "10% of the peak" would be 0 and an engine 1e-7 rad off
  // (contact compliance) would leave the tolerance at its first sample. The floor is 1% of the
  // block's critical angle atan(B/H).
  Scene s;
  s.blocks = {{3.0, 0.5, 1.0, 3750.0, 2500.0}};
  s.blocks.resize(1);
  s.blocks.push_back(BlockDef{0.4, 1.2, 1.0, 1200.0, 2500.0});
  s.initial.theta_rad[1] = 0.1;
  s.run.duration_s = 2.0;
  const reference::Result ref = reference::Simulate(s, GroundMotion());
  ASSERT_EQ(ref.summary.peak_theta_rad[0], 0.0);
  EXPECT_DOUBLE_EQ(AngleTolerance_rad(s, 1, 0.0), 0.01 * std::atan(3.0 / 0.5));
  EngineRun run;
  run.engine = "fake";
  run.history.blocks = 2;
  for (double t = 0.0; t <= 2.0 + 1e-12; t += 0.01) {
    Sample x = ref.trajectory.At(t);
    x.t_s = t;
    x.theta_rad[0] += 1e-7;
    run.history.samples.push_back(x);
  }
  run.summary = nlohmann::json::object();
  const EngineAgreement a = CompareWithReference(s, ref, run);
  EXPECT_TRUE(a.angle(1).within_tolerance);
  EXPECT_NEAR(a.angle(1).horizon_s, 2.0, 1e-9);
  // The 10% rule still holds for a block that moves: block 2's tolerance is 10% of its peak.
  EXPECT_DOUBLE_EQ(a.angle(2).tolerance_rad, 0.1 * ref.summary.peak_theta_rad[1]);
}

TEST(CompareTolerance, ErrorsAreSplitAtThePredictabilityHorizon) {
  const Scene s = testing_util::HousnerHalfAngleRelease(4.0);
  const reference::Result ref = reference::Simulate(s, GroundMotion());
  // Error 1e-4 rad before 2 s and 3e-4 after.
  const EngineRun run =
      FromReference(ref, 0.0, 0.01, 4.0, [](double t) { return t < 2.0 ? 1e-4 : 3e-4; });
  CompareOptions o;
  o.predictability_horizon_s[0] = 2.0;
  const EngineAgreement a = CompareWithReference(s, ref, run, o);
  EXPECT_NEAR(a.angle(1).max_abs_error_predictable_rad, 1e-4, 1e-12);
  EXPECT_NEAR(a.angle(1).max_abs_error_beyond_rad, 3e-4, 1e-12);
  EXPECT_NEAR(a.angle(1).rms_error_beyond_rad, 3e-4, 1e-12);
  EXPECT_NEAR(a.angle(1).samples_beyond, 200, 1);  // the grid is a sum of 0.01 s steps
  EXPECT_EQ(AgreementJson(a)["theta1"]["predictability_horizon_s"], 2.0);
}

}  // namespace
}  // namespace rockbench
