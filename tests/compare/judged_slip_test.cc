// Issue 37: a block whose motion is below the tolerance floor is judged by its peak as well
// (an engine that leaves it at rest does not agree); slip u_k and lift z_k are compared on their
// own scale and decide; a block that slides off its support is an outcome of its own
// (left_support), in the monitor and in the comparison; the console never prints a relative
// peak error for a block below the floor.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "compare/agreement.h"
#include "compare/verdict.h"
#include "engines/common/monitor.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "tests/common/housner_scene.h"
#include "tests/common/reference_suite.h"

namespace rockbench {
namespace {

// The critical angle atan(B / H) of a block, from its definition (not the production code's).
double Alpha(const BlockDef& b) {
  return std::atan(b.width_m / b.height_m);
}

// An engine whose history is the reference's trajectory on a 10 ms grid to t_end, each sample
// changed by `edit`, and whose outcome peaks are those of its samples.
template <class Edit>
EngineRun Engine(const reference::Result& ref, double t_end, Edit edit) {
  EngineRun run;
  run.engine = "fake";
  const int nb = ref.summary.blocks();
  run.history.blocks = nb;
  run.history.slip_and_lift = ref.history.slip_and_lift;
  for (long i = 0;; ++i) {
    const double t = std::min(0.01 * static_cast<double>(i), t_end);
    Sample s = ref.trajectory.At(t);
    s.t_s = t;
    edit(&s);
    run.history.samples.push_back(s);
    if (t >= t_end) break;
  }
  run.summary = nlohmann::json::object();
  run.outcome = RunOutcome(nb);
  for (const Sample& x : run.history.samples) {
    for (int b = 0; b < nb; ++b) {
      if (std::abs(x.theta_rad[b]) > run.outcome.peak_theta_rad[b]) {
        run.outcome.peak_theta_rad[b] = std::abs(x.theta_rad[b]);
        run.outcome.peak_theta_t_s[b] = x.t_s;
      }
    }
  }
  run.outcome.end_t_s = t_end;
  return run;
}

// Housner's block released from 0.7 x its tolerance floor (1% of alpha): its whole motion,
// peak 0.7 floor (the release: free rocking only loses energy), is below the floor, so a block
// that never moves stays within the pointwise tolerance.
class BelowTheFloor : public testing_util::ReferenceSuite<BelowTheFloor> {
 protected:
  static void SetUpTestSuite() {
    Scene scene = testing_util::HousnerHalfAngleRelease(2.0);
    floor_ = 0.01 * Alpha(scene.blocks[0]);
    scene.initial.theta_rad[0] = 0.7 * floor_;
    RunReference(std::move(scene));
  }
  static inline double floor_ = 0.0;
};

TEST_F(BelowTheFloor, AnEngineThatLeavesTheBlockAtRestDoesNotAgree) {
  // The release is the peak (to the rounding of the integration, 1e-12 of it).
  ASSERT_NEAR(ref_->summary.peak_theta_rad[0], 0.7 * floor_, 1e-12 * floor_);
  const EngineRun rest = Engine(*ref_, 2.0, [](Sample* s) {
    s->theta_rad[0] = 0.0;
    s->omega_radps[0] = 0.0;
  });
  const EngineAgreement a = CompareWithReference(*scene_, *ref_, rest);
  // The pointwise check alone passes (|error| <= 0.7 floor < floor): that is the flaw.
  EXPECT_TRUE(a.angle(1).within_tolerance);
  EXPECT_FALSE(a.angle(1).judged);
  EXPECT_NEAR(a.angle(1).floor_rad, floor_, 1e-15);
  // Its peak, 0 against 0.7 floor, is beyond 25% of the reference's (0.175 floor).
  EXPECT_NEAR(a.angle(1).peak_tolerance_rad, 0.25 * 0.7 * floor_, 1e-12 * floor_);
  EXPECT_FALSE(a.angle(1).peak_within_tolerance);
  EXPECT_FALSE(AgreementJson(a)["theta1"]["judged"].get<bool>());
  // Predictable throughout, and with no perturbation members run: not an agreement.
  const Verdict v = MakeVerdict(*scene_, a, Horizons{}, std::nullopt);
  EXPECT_EQ(v.kind, "differs_before_horizon") << v.text;
  EXPECT_FALSE(v.agrees);
  EXPECT_NE(v.text.find("theta1 is not judged point by point alone"), std::string::npos) << v.text;
  EXPECT_NE(v.decided_by.find("theta1 peak"), std::string::npos) << v.decided_by;
  const Verdict q = MakeVerdict(*scene_, a, std::nullopt, std::nullopt);
  EXPECT_EQ(q.kind, "pointwise_differs") << q.text;
}

// Where the reference's model stops deciding (undetermined from 1.0 s here), nothing after it
// is the model's: an engine that rocks like the reference until then and tips to 0.5 rad after
// it is judged on its peak over the compared window (to 1.0 s), and the verdict says the model
// ends there (outside_model), not that the engine's peak differs.
TEST_F(BelowTheFloor, PeaksAreComparedWhereTheModelDecides) {
  reference::Result cut = *ref_;
  cut.summary.undetermined_from_s = 1.0;
  cut.summary.undetermined_detail = "a test's undecided impact";
  const EngineRun tips = Engine(cut, 2.0, [](Sample* s) {
    if (s->t_s > 1.0) s->theta_rad[0] = 0.5;
  });
  const EngineAgreement a = CompareWithReference(*scene_, cut, tips);
  EXPECT_DOUBLE_EQ(a.compared_until_s, 1.0);
  EXPECT_LE(a.angle(1).peak_engine_t_s, 1.0);
  EXPECT_TRUE(a.angle(1).peak_within_tolerance) << a.angle(1).peak_engine_rad;
  const Verdict v = MakeVerdict(*scene_, a, Horizons{}, std::nullopt);
  EXPECT_EQ(v.kind, "outside_model") << v.text;
  // The same rule without the ensemble (compare --quick).
  const Verdict q = MakeVerdict(*scene_, a, std::nullopt, std::nullopt);
  EXPECT_EQ(q.kind, "outside_model") << q.text;
  EXPECT_NE(q.text.find("ends at 1.00 s (a test's undecided impact)"), std::string::npos) << q.text;
}

TEST_F(BelowTheFloor, AnEngineThatRocksLikeItAgrees) {
  // The reference's own motion 10% larger: within the 25% peak tolerance and the floor.
  const EngineRun near = Engine(*ref_, 2.0, [](Sample* s) { s->theta_rad[0] *= 1.1; });
  const EngineAgreement a = CompareWithReference(*scene_, *ref_, near);
  EXPECT_FALSE(a.angle(1).judged);
  EXPECT_TRUE(a.angle(1).peak_within_tolerance);
  const Verdict v = MakeVerdict(*scene_, a, Horizons{}, std::nullopt);
  EXPECT_EQ(v.kind, "agrees") << v.text;
  // The text names the block not judged point by point alone, and why.
  EXPECT_NE(v.text.find("below 5 x the tolerance floor"), std::string::npos) << v.text;
}

TEST_F(BelowTheFloor, ABlockWellAboveTheFloorIsJudgedPointByPoint) {
  // Released from half its critical angle: 50 floors of motion.
  const Scene s = testing_util::HousnerHalfAngleRelease(2.0);
  const reference::Result ref = reference::Simulate(s, GroundMotion());
  const EngineAgreement a = CompareWithReference(s, ref, Engine(ref, 2.0, [](Sample*) {}));
  EXPECT_TRUE(a.angle(1).judged);
  EXPECT_TRUE(AgreementJson(a)["theta1"]["judged"].get<bool>());
}

// The shipped scene whose top block slides off (mu 0.2 on block 1, a 0.5 g pulse): the
// reference slips block 2 by 0.85 m and it leaves block 1 at 0.86 s.
class SlidesOff : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(
        LoadScene(std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/top_block_slides_off.toml"));
    motion_ = new GroundMotion(GroundMotion::FromScene(*scene_));
    ref_ = new reference::Result(reference::Simulate(*scene_, *motion_));
  }
  static void TearDownTestSuite() {
    delete ref_;
    delete motion_;
    delete scene_;
  }
  // The reference's peak |u2| over its samples.
  static double PeakU2() {
    double p = 0.0;
    for (const Sample& s : ref_->history.samples) p = std::max(p, std::abs(s.u_m[1]));
    return p;
  }
  static Scene* scene_;
  static GroundMotion* motion_;
  static reference::Result* ref_;
};
Scene* SlidesOff::scene_ = nullptr;
GroundMotion* SlidesOff::motion_ = nullptr;
reference::Result* SlidesOff::ref_ = nullptr;

TEST_F(SlidesOff, TheReferenceLeavesItsSupportRatherThanOverturning) {
  ASSERT_TRUE(ref_->history.slip_and_lift);
  EXPECT_EQ(ref_->summary.status, RunStatus::kLeftSupport);
  ASSERT_TRUE(ref_->summary.left_support_block.has_value());
  EXPECT_EQ(*ref_->summary.left_support_block, 2);
  EXPECT_FALSE(ref_->summary.overturn_block.has_value());
  // Block 2's base centre is past b1 + b2 = 0.85 m from block 1's top centre when it leaves;
  // its slip u2 (the tilted corner's) is of that size.
  EXPECT_GT(PeakU2(), 0.5);
}

TEST_F(SlidesOff, SlipTwiceTheReferencesDiffersAndSlipWithinTheToleranceAgrees) {
  const double end = ref_->trajectory.end_s();
  const double peak = PeakU2();
  // Tolerance 10% of the reference's peak slip; the floor 1% alpha B (2.2 mm for block 2 here)
  // is far below it.
  const double tol = 0.1 * peak;
  ASSERT_GT(tol, 0.01 * Alpha(scene_->blocks[1]) * scene_->blocks[1].width_m);

  auto with_left_support = [&](EngineRun run) {
    run.outcome.status = RunStatus::kLeftSupport;
    run.outcome.left_support_block = 2;
    run.outcome.left_support_t_s = ref_->summary.left_support_t_s;
    return run;
  };
  const EngineRun twice = with_left_support(Engine(*ref_, end, [](Sample* s) { s->u_m[1] *= 2; }));
  const EngineAgreement a = CompareWithReference(*scene_, *ref_, twice);
  ASSERT_EQ(a.blocks(), 2);
  ASSERT_TRUE(a.body(2).slip.has_value());
  EXPECT_NEAR(a.body(1 + 1).slip->tolerance_m, tol, 1e-12);
  // The largest error is the reference's slip at the engine's last sample (the end).
  EXPECT_GT(a.body(1 + 1).slip->max_abs_error_m, 0.9 * peak);
  EXPECT_FALSE(a.body(1 + 1).slip->within_tolerance);
  const nlohmann::json j = AgreementJson(a);
  for (const char* key : {"max_abs_error_m", "final_reference_m", "final_engine_m", "tolerance_m"})
    EXPECT_TRUE(j["u2"].contains(key)) << key;
  EXPECT_NEAR(j["u2"]["final_engine_m"].get<double>(),
              2.0 * j["u2"]["final_reference_m"].get<double>(), 1e-12);
  // The angles are the reference's: the slip alone decides.
  EXPECT_TRUE(a.angle(2).within_tolerance);
  const Verdict v = MakeVerdict(*scene_, a, Horizons{}, std::nullopt);
  EXPECT_EQ(v.kind, "differs_before_horizon") << v.text;
  EXPECT_NE(v.text.find("u2 (slip of block 2 on block 1) leaves its tolerance"), std::string::npos)
      << v.text;
  EXPECT_EQ(v.decided_by.rfind("u2 error", 0), 0u) << v.decided_by;

  // 5% more slip: at most half the tolerance.
  const EngineRun close =
      with_left_support(Engine(*ref_, end, [](Sample* s) { s->u_m[1] *= 1.05; }));
  const EngineAgreement b = CompareWithReference(*scene_, *ref_, close);
  EXPECT_TRUE(b.body(1 + 1).slip->within_tolerance);
  EXPECT_LE(b.body(1 + 1).slip->max_abs_error_m, 0.05 * peak + 1e-12);
  const Verdict w = MakeVerdict(*scene_, b, Horizons{}, std::nullopt);
  EXPECT_EQ(w.kind, "agrees") << w.text;
}

TEST_F(SlidesOff, LeavingTheSupportAgreesOnlyWithLeavingTheSupport) {
  const double end = ref_->trajectory.end_s();
  EngineRun off = Engine(*ref_, end, [](Sample*) {});
  off.outcome.status = RunStatus::kLeftSupport;
  off.outcome.left_support_block = 2;
  off.outcome.left_support_t_s = ref_->summary.left_support_t_s + 0.001;
  const EngineAgreement a = CompareWithReference(*scene_, *ref_, off);
  EXPECT_TRUE(a.left_support_agree);
  EXPECT_TRUE(a.overturn_agree);
  ASSERT_TRUE(a.left_support_time_error_s.has_value());
  EXPECT_NEAR(*a.left_support_time_error_s, 0.001, 1e-12);
  EXPECT_EQ(a.final_mode_reference, "left_support");
  EXPECT_EQ(a.final_mode_engine, "left_support");
  const Verdict v = MakeVerdict(*scene_, a, Horizons{}, std::nullopt);
  EXPECT_EQ(v.kind, "agrees") << v.text;
  EXPECT_NE(v.text.find("block 2 leaves its support in both runs"), std::string::npos) << v.text;
  EXPECT_EQ(AgreementJson(a)["left_support"]["engine_block"], 2);

  // The same motion, but the engine calls it an overturn of block 2: not the same outcome.
  EngineRun over = Engine(*ref_, end, [](Sample*) {});
  over.outcome.status = RunStatus::kOverturned;
  over.outcome.overturned_block = 2;
  over.outcome.overturn_t_s = ref_->summary.left_support_t_s;
  const EngineAgreement b = CompareWithReference(*scene_, *ref_, over);
  EXPECT_FALSE(b.left_support_agree);
  EXPECT_FALSE(b.overturn_agree);
  const Verdict w = MakeVerdict(*scene_, b, Horizons{}, std::nullopt);
  EXPECT_EQ(w.kind, "differs_before_horizon") << w.text;
  EXPECT_NE(w.text.find("block 2 overturns in the engine's run, block 2 leaves its support in "
                        "the reference's"),
            std::string::npos)
      << w.text;
}

// The monitor: block 2 (0.5 x 0.25 m) sliding flat at 1 m/s on block 1 (1.2 x 0.4 m) leaves it
// when its base's middle is b1 + b2 = 0.85 m from block 1's top middle: at 0.85 s, interpolated
// inside the step. Block 1 never leaves the ground, however far it slides.
TEST(MonitorLeftSupport, ABlockWhoseBaseNoLongerOverlapsItsSupportHasLeftIt) {
  EngineInput in;
  in.blocks = {{1.2, 0.4, 1.0, 1200.0, 2500.0}, {0.5, 0.25, 1.0, 312.5, 2500.0}};
  in.time_step_s = 0.1;
  in.run.output_interval_s = 0.1;
  in.run.duration_s = 2.0;
  in.steps = 20;
  in.slip_and_lift = true;
  Monitor m(in);
  auto state = [&](double t, double x1, double x2) {
    StepReadout r(2);
    r.t_s = t;
    r.blocks[0].x_m = x1;
    r.blocks[0].y_m = 0.2;
    r.blocks[1].x_m = x2;
    r.blocks[1].y_m = 0.4 + 0.125;
    r.blocks[1].vx_mps = 1.0;
    return r;
  };
  m.Start(state(0.0, 0.0, 0.0));
  bool running = true;
  int n = 0;
  while (running && n < 20) {
    ++n;
    const double t = 0.1 * n;
    // Block 1 slides 5 m with block 2 riding on it, so it never leaves the (infinite) ground;
    // block 2 moves 1 m/s relative to block 1.
    running = m.Step(n, state(t, 5.0 * t, 5.0 * t + 1.0 * t));
  }
  EXPECT_EQ(n, 9);  // 0.9 s: the first step whose state is past 0.85 m
  EXPECT_EQ(m.status(), RunStatus::kLeftSupport);
  const RunOutcome o = m.Outcome();
  EXPECT_EQ(o.left_support_block, 2);
  EXPECT_NEAR(o.left_support_t_s, 0.85, 1e-12);  // linear in t: the interpolation is exact
  EXPECT_EQ(o.overturned_block, 0);
  EXPECT_EQ(m.Summary()["left_support"]["block"], 2);
  EXPECT_EQ(m.Summary()["status"], "left_support");
}

}  // namespace
}  // namespace rockbench
