// The comparison of N >= 3 blocks (issue 23): errors, horizons, verdicts, the statistical
// comparison of perturbation members and the perturbed inputs, block by block, on 3- and 6-block
// stacks run by the reference (the engines refuse N >= 3 until they are generalised), with
// "engines" made of the reference's own trajectory.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/stack_scene.h"
#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "compare/verdict.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/summary.h"
#include "run/tolerance.h"

namespace rockbench {
namespace {

using testing_util::StackScene;

// An "engine" that reports the reference's own trajectory on the reference's output grid, with
// `offset_rad` added to block `block`'s angle (1-based; 0: none), and the reference's peaks.
EngineRun FromReference(const reference::Result& ref, int blocks, int block, double offset_rad) {
  EngineRun run;
  run.engine = "fake";
  run.history.blocks = blocks;
  for (int k = 0;; ++k) {
    const double t = 0.01 * k;
    if (t > ref.trajectory.end_s() + 1e-12) break;
    Sample s = ref.trajectory.At(t);
    s.t_s = t;
    if (block > 0) s.theta_rad[block - 1] += offset_rad;
    run.history.samples.push_back(s);
  }
  run.history.events = ref.history.events;
  run.summary = nlohmann::json::object();
  // The peaks an engine measures at every step: the reference's own.
  run.outcome = RunOutcome(blocks);
  run.outcome.peak_theta_rad = ref.summary.peak_theta_rad;
  run.outcome.peak_theta_t_s = ref.summary.peak_theta_t_s;
  run.wall_s = 0.5;
  return run;
}

class StackCompareTest : public ::testing::TestWithParam<int> {
 protected:
  int n() const { return GetParam(); }
};

// The same trajectory: the engine's samples are the reference's dense output at the same
// times, so every error is exactly zero (the same function of the same time).
TEST_P(StackCompareTest, AHistoryComparedWithItselfHasNoErrorOnAnyBlock) {
  const Scene s = StackScene(n(), 1.5);
  const reference::Result ref = reference::Simulate(s, GroundMotion());
  ASSERT_EQ(ref.summary.blocks(), n());
  const EngineAgreement a = CompareWithReference(s, ref, FromReference(ref, n(), 0, 0.0));
  ASSERT_EQ(a.blocks(), n());
  for (int b = 1; b <= n(); ++b) {
    const AngleAgreement& g = a.angle(b);
    EXPECT_EQ(g.max_abs_error_rad, 0.0) << "theta" << b;
    EXPECT_EQ(g.rms_error_rad, 0.0) << "theta" << b;
    EXPECT_TRUE(g.within_tolerance) << "theta" << b;
    EXPECT_EQ(g.peak_rel_error, 0.0) << "theta" << b;
    EXPECT_EQ(a.body(b).final_angle_error_rad, 0.0) << "theta" << b;
    // Each block's tolerance is its own rule (10% of its peak, at least 1% of its critical
    // angle), not block 1's or 2's.
    EXPECT_DOUBLE_EQ(g.tolerance_rad, AngleTolerance_rad(s, b, ref.summary.peak_theta_rad[b - 1]));
  }
  EXPECT_TRUE(a.final_agree);
  EXPECT_TRUE(a.overturn_agree);
  EXPECT_EQ(a.impacts.matched, a.impacts.reference_impacts);
  const Verdict v = MakeVerdict(s, a, std::nullopt, std::nullopt);
  EXPECT_EQ(v.kind, "pointwise_only") << v.text;
}

// Block 3 offset by a known angle: exactly that error on block 3 (to the rounding of adding
// it, a few 1e-17 rad at these angles: 1e-15 allows 100 ulps), none on the others; beyond the
// tolerance, the verdict differs and names theta3.
TEST_P(StackCompareTest, AnOffsetOnBlock3IsThatErrorOnBlock3Only) {
  const Scene s = StackScene(n(), 1.5);
  const reference::Result ref = reference::Simulate(s, GroundMotion());
  // Above block 3's tolerance, 10% of its peak: 2.8e-3 rad of 3 blocks, 2e-3 of 6.
  const double offset = 0.01;
  const EngineAgreement a = CompareWithReference(s, ref, FromReference(ref, n(), 3, offset));
  ASSERT_EQ(a.blocks(), n());
  for (int b = 1; b <= n(); ++b) {
    const AngleAgreement& g = a.angle(b);
    if (b == 3) {
      EXPECT_NEAR(g.max_abs_error_rad, offset, 1e-15);
      EXPECT_NEAR(g.rms_error_rad, offset, 1e-15);
      EXPECT_NEAR(a.body(b).final_angle_error_rad, offset, 1e-15);
      EXPECT_FALSE(g.within_tolerance);
      EXPECT_EQ(g.horizon_s, 0.0);  // outside from the first sample
    } else {
      EXPECT_EQ(g.max_abs_error_rad, 0.0) << "theta" << b;
      EXPECT_TRUE(g.within_tolerance) << "theta" << b;
    }
  }
  EXPECT_FALSE(a.final_agree);
  const Verdict v = MakeVerdict(s, a, std::nullopt, std::nullopt);
  EXPECT_EQ(v.kind, "pointwise_differs");
  EXPECT_NE(v.text.find("theta3 leaves the local tolerance"), std::string::npos) << v.text;
  EXPECT_EQ(v.text.find("theta1 leaves"), std::string::npos) << v.text;
  EXPECT_EQ(v.decided_by.rfind("theta3 error", 0), 0u) << v.decided_by;
  // With a reference predictable throughout, the same error is the engine's: differs before
  // the horizon, on theta3 (the stack's verdict is the worst of its blocks).
  Horizons h;
  const Verdict vh = MakeVerdict(s, a, h, std::nullopt);
  EXPECT_EQ(vh.kind, "differs_before_horizon");
  EXPECT_NE(vh.text.find("theta3 leaves"), std::string::npos) << vh.text;
  // A horizon on block 3 before its agreement horizon excuses it: the engine agrees up to it.
  h.horizon_s[2] = 0.0;
  const Verdict vb = MakeVerdict(s, a, h, std::nullopt);
  EXPECT_EQ(vb.kind, "agrees_to_horizon") << vb.text;
}

// comparison.json names every block (theta1..thetaN, final.thetaK_error_rad, the reference's
// peaks and tolerances, scene.blocks) and comparison.csv has one row per block.
TEST_P(StackCompareTest, JsonAndCsvHaveEveryBlock) {
  const Scene s = StackScene(n(), 1.0);
  const reference::Result ref = reference::Simulate(s, GroundMotion());
  EngineRun run = FromReference(ref, n(), n(), 1e-4);
  run.engine = "bullet";
  const EngineAgreement a = CompareWithReference(s, ref, run);
  const nlohmann::json j = ComparisonJson(s, ref, 0.01, {a});
  EXPECT_EQ(j["scene"]["blocks"], n());
  EXPECT_EQ(j["scene"]["two_blocks"], false);
  const nlohmann::json& e = j["engines"]["bullet"];
  for (int b = 1; b <= n(); ++b) {
    const std::string th = "theta" + std::to_string(b);
    ASSERT_TRUE(e.contains(th)) << th;
    EXPECT_TRUE(e[th]["max_abs_error_rad"].is_number()) << th;
    EXPECT_TRUE(e["final"].contains(th + "_error_rad")) << th;
    EXPECT_TRUE(j["reference"].contains("peak_" + th + "_rad")) << th;
    EXPECT_TRUE(j["tolerance"].contains(th + "_rad")) << th;
  }
  EXPECT_FALSE(e.contains("theta" + std::to_string(n() + 1)));
  EXPECT_NEAR(e["theta" + std::to_string(n())]["max_abs_error_rad"].get<double>(), 1e-4, 1e-15);
  std::istringstream in(ComparisonCsv({a}));
  std::string header, line;
  std::getline(in, header);
  int rows = 0;
  auto fields = [](const std::string& x) { return std::count(x.begin(), x.end(), ',') + 1; };
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(line.rfind("bullet," + std::to_string(rows) + ",", 0), 0u) << line;
    EXPECT_EQ(fields(line), fields(header));
  }
  EXPECT_EQ(rows, n());
}

INSTANTIATE_TEST_SUITE_P(ThreeAndSixBlocks, StackCompareTest, ::testing::Values(3, 6));

// An impact of block k on block k - 1 ("interfaceK_impact", N >= 3) is an impact the
// comparison counts, its landing rate block k's relative to block k - 1.
TEST(StackCompare, InterfaceImpactsOfEveryBlockAreCounted) {
  History h;
  h.blocks = 4;
  auto impact = [](const char* kind, std::vector<double> w) {
    Event e(4);
    e.kind = kind;
    e.omega_before_radps = std::move(w);
    return e;
  };
  h.events = {impact("ground_impact", {-0.5, 0, 0, 0}),
              impact("interface2_impact", {0.0, 0.3, 0.3, 0.3}),
              impact("interface4_impact", {0.1, 0.1, 0.1, 0.11}),  // 0.01 rad/s: too slow
              impact("interface3_impact", {0.1, 0.1, -0.2, -0.2}), impact("transition", {})};
  EXPECT_EQ(CountComparedImpacts(h, 0.02), 3);
  EXPECT_EQ(CountComparedImpacts(h, 0.005), 4);
}

// Perturbation members of N blocks: each interface's relative angle and rate is perturbed
// within initial_rel, a closed interface stays closed, and member i's inputs depend only on
// (seed, i).
TEST(StackPerturbation, EveryInterfaceIsPerturbedWithinItsSize) {
  Scene s = StackScene(5, 1.0);
  s.initial.theta_rad[3] = s.initial.theta_rad[2];  // block 4 flat on block 3
  s.compare.initial_rel = 0.01;
  for (int m = 0; m < 20; ++m) {
    const MemberInput in = PerturbedInput(s, GroundMotion(), m);
    ASSERT_EQ(in.perturbation.theta_factor.size(), 5u);
    ASSERT_EQ(in.perturbation.omega_factor.size(), 5u);
    const InitialState& p = in.scene.initial;
    EXPECT_EQ(p.theta_rad[3], p.theta_rad[2]) << "member " << m;
    for (int k = 1; k < 5; ++k) {
      const double nominal = s.initial.theta_rad[k] - s.initial.theta_rad[k - 1];
      const double member = p.theta_rad[k] - p.theta_rad[k - 1];
      if (nominal == 0.0) continue;
      // 1% and the rounding of differences of ~0.03 rad (1e-12 relative).
      EXPECT_LE(std::abs(member / nominal - 1.0), 0.01 + 1e-12) << "member " << m << " k " << k;
    }
    const MemberInput again = PerturbedInput(s, GroundMotion(), m);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(again.scene.initial.theta_rad[k], p.theta_rad[k]);
  }
  // A factor per body: two blocks draw two of each.
  const Scene two = StackScene(2, 1.0);
  EXPECT_EQ(PerturbedInput(two, GroundMotion(), 3).perturbation.theta_factor.size(), 2u);
}

// The reference's perturbation members of a 3-block stack without any perturbation: every
// block's spread is zero and no block has a horizon; the band file has every block's columns
// and the outcomes file every block's peak.
TEST(StackPerturbation, NoPerturbationMeansNoSpreadOnAnyBlock) {
  Scene s = StackScene(3, 1.0);
  s.compare.amplitude_rel = s.compare.sample_precision = s.compare.initial_rel = 0.0;
  const reference::Result nominal = reference::Simulate(s, GroundMotion());
  std::vector<double> tol;
  for (int b = 0; b < 3; ++b) {
    tol.push_back(AngleTolerance_rad(s, b + 1, nominal.summary.peak_theta_rad[b]));
  }
  const ReferencePerturbationMembers e =
      RunReferencePerturbationMembers(s, GroundMotion(), nominal, 3, tol, 1, 0.02);
  ASSERT_EQ(e.blocks, 3);
  for (int b = 0; b < 3; ++b) {
    EXPECT_EQ(e.max_spread_rad[b], 0.0) << b;
    EXPECT_FALSE(e.horizon_s[b].has_value()) << b;
    EXPECT_EQ(e.tolerance_rad[b], tol[b]);
  }
  const std::string band = PerturbationBandCsv(e);
  EXPECT_EQ(band.substr(0, band.find('\n')),
            "t,theta1_lo,theta1_hi,theta1_spread,theta1_tol,theta2_lo,theta2_hi,theta2_spread,"
            "theta2_tol,theta3_lo,theta3_hi,theta3_spread,theta3_tol");
  const std::string outcomes = OutcomesCsv(e.outcomes, e.perturbations, 3);
  EXPECT_NE(outcomes.find("peak_theta3_rad,peak_theta3_t_s,residual_theta3_rad,rms_theta1_rad,"
                          "rms_theta2_rad,rms_theta3_rad,impacts\n"),
            std::string::npos);
  // Every member is the nominal run: its peaks are the nominal's, block by block.
  for (const MemberOutcome& o : e.outcomes) {
    for (int b = 0; b < 3; ++b) EXPECT_EQ(o.peak_rad[b], nominal.summary.peak_theta_rad[b]);
  }
  const nlohmann::json j = PredictabilityJson(s, e);
  EXPECT_TRUE(j["horizon_s"].contains("theta3"));
  EXPECT_TRUE(j["horizon_s"]["theta3"].is_null());
  EXPECT_EQ(j["spread_rad"]["theta3"], 0.0);
}

// `count` members of `blocks` blocks whose outcomes spread evenly over the same ranges for any
// count (member i at the quantile (i + 1/2) / count): two such sets are samples of one
// distribution. `biased_block` (1-based; 0: none) has its peak scaled by 1 + bias.
std::vector<MemberOutcome> Members(int count, int blocks, int biased_block, double bias) {
  std::vector<MemberOutcome> out(count);
  for (int i = 0; i < count; ++i) {
    const double q = (i + 0.5) / count;
    out[i].member = i;
    for (int b = 0; b < blocks; ++b) {
      out[i].peak_rad[b] = 0.05 + 0.01 * b + 0.0124 * q;
      out[i].peak_t_s[b] = 1.0 + 0.3 * q;
      out[i].rms_rad[b] = 0.01 + 0.006 * q;
      out[i].residual_rad[b] = 0.0;
    }
    if (biased_block > 0) out[i].peak_rad[biased_block - 1] *= 1.0 + bias;
  }
  return out;
}

// The statistical comparison beyond the horizon tests every block's peak, peak time, RMS and
// residual in one Holm family with the overturning; a bias on block 6's peak alone is found
// there and nowhere else.
TEST(StackStatistics, EveryBlockIsTestedAndABiasOnOneBlockIsFoundThere) {
  const int n = 6;
  const std::vector<double> tol(n, 0.005);
  const std::vector<MemberOutcome> ref = Members(32, n, 0, 0.0);
  const StatisticalComparison same =
      ComparePerturbationMembers(ref, Members(16, n, 0, 0.0), tol, 0.01);
  ASSERT_TRUE(same.available);
  EXPECT_EQ(same.blocks, n);
  int family = 0;
  for (const QuantityComparison& q : same.quantities) family += q.in_family ? 1 : 0;
  EXPECT_EQ(family, 4 * n);  // peak, peak time, RMS, residual of each block
  for (int b = 1; b <= n; ++b) {
    const std::string th = "theta" + std::to_string(b);
    for (const std::string& key : {"peak_" + th + "_rad", "peak_" + th + "_t_s",
                                   "rms_" + th + "_rad", "residual_" + th + "_rad"}) {
      bool found = false;
      for (const QuantityComparison& q : same.quantities) found = found || q.key == key;
      EXPECT_TRUE(found) << key;
    }
  }
  EXPECT_TRUE(same.consistent);
  // A 40% bias on block 6's peak: far outside the members' spread (0.0124 rad at 0.1 rad).
  const StatisticalComparison biased =
      ComparePerturbationMembers(ref, Members(16, n, 6, 0.4), tol, 0.01);
  ASSERT_TRUE(biased.available);
  EXPECT_FALSE(biased.consistent);
  ASSERT_EQ(biased.rejected.size(), 1u);
  EXPECT_EQ(biased.rejected[0], "peak_theta6_rad");
  // Overturning by block: block 5 in every engine member, none in the reference's.
  std::vector<MemberOutcome> over = Members(16, n, 0, 0.0);
  for (MemberOutcome& o : over) o.overturned_block = 5;
  const StatisticalComparison ov = ComparePerturbationMembers(ref, over, tol, 0.01);
  EXPECT_EQ(ov.overturn_engine[5], 16);
  EXPECT_EQ(ov.overturn_reference[0], 32);
  EXPECT_NE(std::find(ov.rejected.begin(), ov.rejected.end(), "overturn"), ov.rejected.end());
  const nlohmann::json j = StatisticsJson(ov);
  EXPECT_EQ(j["tests"]["overturn"]["engine"]["block5"], 16);
  EXPECT_EQ(j["tests"]["overturn"]["engine"]["block6"], 0);
  EXPECT_FALSE(j["tests"]["overturn"]["engine"].contains("block7"));
  Verdict v;
  EngineAgreement a;
  a.bodies.resize(n);
  Horizons h;
  h.horizon_s[0] = 0.5;
  v = MakeVerdict(StackScene(n, 1.0), a, h, ov);
  EXPECT_EQ(v.kind, "differs_beyond_horizon");
  EXPECT_NE(v.text.find("overturning (engine 16 of 16 against 0 of 32"), std::string::npos)
      << v.text;
}

// The time after which the base cannot start a 3-block stack rocking: the rest reactions of
// the pivot chain. A pulse 25% above the smallest tipping threshold decides until its end; one
// whose 1.25-fold is below the threshold never opens a face (0).
TEST(StackPerturbation, SettledAfterUsesEveryInterfaceOfTheStack) {
  Scene s = StackScene(3, 2.0);
  for (double& t : s.initial.theta_rad) t = 0.0;
  // The smallest threshold b_k g / H_k over the interfaces (docs/n-blocks.md): H_k the height of
  // the mass centre of blocks k..N above block k's base.
  double threshold = 1e9;
  for (int k = 0; k < 3; ++k) {
    double m = 0.0, my = 0.0, base = 0.0;
    for (int j = k; j < 3; ++j) {
      m += s.blocks[j].mass_kg;
      my += s.blocks[j].mass_kg * (base + 0.5 * s.blocks[j].height_m);
      base += s.blocks[j].height_m;
    }
    threshold = std::min(threshold, 0.5 * s.blocks[k].width_m * s.run.gravity_mps2 / (my / m));
  }
  auto pulse = [&](double amplitude_mps2) {
    Scene p = s;
    MotionDef d;
    d.key = "base.horizontal";
    d.kind = MotionKind::kRectangularPulse;
    d.amplitude_g = amplitude_mps2 / kStandardGravity_mps2;
    d.duration_s = 0.5;
    d.start_s = 0.2;
    p.horizontal = d;
    return SettledAfter_s(p, GroundMotion::FromScene(p));
  };
  // The pulse ends at 0.7 s; the last scan point where the face opens is within 1 ms of it.
  EXPECT_NEAR(pulse(1.1 * threshold), 0.7, 2e-3);
  EXPECT_EQ(pulse(0.7 * threshold), 0.0);
}

}  // namespace
}  // namespace rockbench
