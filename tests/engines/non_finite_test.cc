// Never a NaN result (issue 21), for every engine of the build: a base motion absurd enough to
// drive an engine's bodies past the range of a double ends its run with status "non_finite",
// naming the quantity and the time, at the last finite state; the history, the events and the
// summary hold only finite numbers; the verdict on such a run is the engine's own failure
// (violates_model, decided by "non_finite at t = ..."). The motion is built in code
// (MotionComponent::FromSamples): the scene reader refuses such records up front.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/engine_suite.h"
#include "common/spike_motion.h"
#include "common/thesis_scene.h"
#include "compare/agreement.h"
#include "compare/perturbation_members.h"
#include "compare/verdict.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/reference_engine.h"
#include "run/summary.h"
#include "scene/history.h"
#include "tests/common/json_checks.h"

namespace rockbench {
namespace {

constexpr double kDt = testing_util::kSpikeDt_s;  // s, the spike record's sample interval
using testing_util::Spike;

bool Finite(const Sample& s) {
  return std::isfinite(s.t_s) && std::isfinite(s.theta_rad[0]) && std::isfinite(s.theta_rad[1]) &&
         std::isfinite(s.omega_radps[0]) && std::isfinite(s.omega_radps[1]);
}

bool Finite(const Event& e) {
  return std::isfinite(e.t_s) && std::isfinite(e.omega_before_radps[0]) &&
         std::isfinite(e.omega_before_radps[1]) && std::isfinite(e.omega_after_radps[0]) &&
         std::isfinite(e.omega_after_radps[1]) && std::isfinite(e.energy_before_j) &&
         std::isfinite(e.energy_after_j);
}

class EngineNonFinite : public ::testing::TestWithParam<std::string> {};

// The thesis's stack at rest under a 1e200 g sample at 0.50 s (ramp from 0.49 s): the first
// engine step inside the ramp accelerates the blocks by at least 1e-2 of it (the step is at most
// a hundredth of the sample interval), so the kinetic energy (or the pose) overflows in that
// step; before 0.49 s the record is zero and nothing can.
TEST_P(EngineNonFinite, AnAbsurdSpikeEndsTheRunAtItsLastFiniteState) {
  ASSERT_NE(FindEngine(GetParam()), nullptr) << GetParam() << " is not built";
  Scene scene = testing_util::ThesisFreeRockingStack(2.0, 0.01);
  scene.initial = {};
  const GroundMotion motion = Spike(1e200, 50);
  const EngineRun run = RunEngine(GetParam(), scene, motion);
  const nlohmann::json& j = run.summary;

  ASSERT_EQ(run.outcome.status, RunStatus::kNonFinite) << j.value("status_detail", "");
  ASSERT_TRUE(j.contains("non_finite"));
  const nlohmann::json& nf = j["non_finite"];
  const std::string quantity = nf["quantity"].get<std::string>();
  const std::string value = nf["value"].get<std::string>();
  const double t_s = nf["t_s"].get<double>(), last_s = nf["last_finite_t_s"].get<double>();
  EXPECT_NE(j["status_detail"].get<std::string>().find(quantity + " is " + value + " at t = "),
            std::string::npos)
      << j["status_detail"];
  // Within the ramp, to an engine step (the engine's steps need not land on 0.49 s).
  EXPECT_GT(t_s, 0.49 - 1e-9);
  EXPECT_LE(t_s, 0.50 + 1e-9);
  EXPECT_LT(last_s, t_s);
  EXPECT_GE(last_s, 0.48);

  // The history ends at the last finite state; everything in it, the events and the summary
  // is finite.
  ASSERT_FALSE(run.history.samples.empty());
  EXPECT_EQ(run.history.samples.back().t_s, last_s);
  EXPECT_EQ(run.outcome.end_t_s, last_s);
  for (const Sample& s : run.history.samples) EXPECT_TRUE(Finite(s)) << "t = " << s.t_s;
  bool has_event = false;
  for (const Event& e : run.history.events) {
    EXPECT_TRUE(Finite(e)) << e.kind << " at " << e.t_s;
    EXPECT_LE(e.t_s, last_s) << e.kind;
    if (e.kind == "non_finite") {
      has_event = true;
      EXPECT_EQ(e.t_s, last_s);
    }
  }
  EXPECT_TRUE(has_event);
  EXPECT_TRUE(testing_util::AllFinite(j)) << j.dump(2);
  EXPECT_TRUE(std::isfinite(run.outcome.peak_theta_rad[0]));
  EXPECT_TRUE(std::isfinite(run.outcome.peak_theta_rad[1]));
  EXPECT_LE(run.outcome.peak_theta_t_s[0], last_s);
  EXPECT_TRUE(j["violations"]["blow_up"].get<bool>());

  // The verdict: the engine's own failure, whatever the reference did on the same input.
  const reference::Result ref = reference::Simulate(scene, motion);
  const EngineAgreement a = CompareWithReference(scene, ref, run);
  const Verdict v = MakeVerdict(scene, a, std::nullopt, std::nullopt);
  EXPECT_EQ(v.kind, "violates_model") << v.text;
  EXPECT_FALSE(v.agrees);
  EXPECT_EQ(v.decided_by.rfind("non_finite at t = ", 0), 0u) << v.decided_by;
  EXPECT_NE(v.decided_by.find(quantity), std::string::npos) << v.decided_by;
}

// The harness's side, engine-independent: what a failed reference means for the verdict, the
// convergence check and summary.json.

// The thesis's stack at rest, 2 s.
Scene StackAtRest() {
  Scene scene = testing_util::ThesisFreeRockingStack(2.0, 0.01);
  scene.initial = {};
  return scene;
}

// The reference as an engine run (its summary as summary.json has it), on `motion`.
EngineRun ReferenceAsEngine(const Scene& scene, const GroundMotion& motion) {
  return RunEngine("reference", scene, motion, {.check_convergence = false});
}

// An engine that agrees, compared with a reference that failed: no verdict (reference_failed,
// the console's NO VERDICT), decided by the reference's failure and its time.
TEST(NonFiniteHarness, AFailedReferenceGivesNoVerdict) {
  const Scene scene = StackAtRest();
  const reference::Result failed = reference::Simulate(scene, Spike(1e200, 50));
  ASSERT_EQ(failed.summary.status, RunStatus::kNonFinite);
  const EngineRun fine = ReferenceAsEngine(scene, Spike(0.0, 50));
  ASSERT_EQ(fine.outcome.status, RunStatus::kAtRest);
  const EngineAgreement a = CompareWithReference(scene, failed, fine);
  for (const std::optional<Horizons>& h : {std::optional<Horizons>(), std::optional(Horizons{})}) {
    const Verdict v = MakeVerdict(scene, a, h, std::nullopt);
    EXPECT_EQ(v.kind, "reference_failed") << v.text;
    EXPECT_FALSE(v.agrees);
    EXPECT_EQ(VerdictLabel(v.kind), "NO VERDICT");
    EXPECT_EQ(v.decided_by.rfind("reference non_finite at t = ", 0), 0u) << v.decided_by;
  }
  // Nothing after the reference's last finite state is compared.
  EXPECT_LE(a.compared_until_s, failed.summary.non_finite_last_t_s);
}

// The finding, end to end: one 1e20 g sample under the stack at rest. The default
// reference (dopri5) stops on an uplift, its witness (dop853 at rtol 1e-14) goes non-finite:
// the run reports the witness's failure, never the other run with a warning, and summary.json
// has the non_finite object and no number that is not finite.
TEST(NonFiniteHarness, TheWitnessNeverHidesAFailure) {
  const Scene scene = StackAtRest();
  const EngineRun run = RunEngine("reference", scene, Spike(1e20, 10));
  ASSERT_NE(ReferenceResultOf(run.extension.get()), nullptr);
  const CheckedReference& checked = *ReferenceResultOf(run.extension.get());
  ASSERT_TRUE(checked.check.has_value());
  ASSERT_NE(checked.nominal.summary.status, RunStatus::kNonFinite)
      << checked.nominal.summary.status;
  ASSERT_EQ(checked.witness->summary.status, RunStatus::kNonFinite);
  EXPECT_TRUE(checked.check->witness_non_finite);
  EXPECT_EQ(checked.used().summary.status, RunStatus::kNonFinite);
  EXPECT_EQ(run.summary["status"], "non_finite");
  EXPECT_EQ(run.summary["convergence"]["used"], "witness");
  EXPECT_TRUE(run.summary.contains("non_finite"));
  EXPECT_TRUE(testing_util::AllFinite(run.summary)) << run.summary.dump(2);
  EXPECT_EQ(NonFiniteText(run).rfind("reference: ", 0), 0u);
  for (const Sample& smp : run.history.samples) EXPECT_TRUE(Finite(smp)) << smp.t_s;
}

// Members that ended non_finite: a failed reference member leaves the predictability unknown
// (reference_failed); a failed engine member is the engine's failure (violates_model). Neither
// enters the statistics.
TEST(NonFiniteHarness, FailedEnsembleMembersAreNeverAnAgreement) {
  const Scene scene = StackAtRest();
  const EngineRun ok = ReferenceAsEngine(scene, Spike(0.0, 50));
  const reference::Result ref = reference::Simulate(scene, Spike(0.0, 50));
  const EngineAgreement a = CompareWithReference(scene, ref, ok);
  std::vector<MemberOutcome> members(12);
  for (int i = 0; i < 12; ++i) {
    members[i] = OutcomeOf(ok, scene, 0.02);
    members[i].member = i;
  }
  std::vector<MemberOutcome> engine = members;
  engine[3].status = RunStatus::kNonFinite;
  engine[3].detail = "energy is +inf at t = 0.4901 s";
  const double tol[2] = {0.01, 0.01};
  const StatisticalComparison st = ComparePerturbationMembers(members, engine, tol, 0.01);
  EXPECT_EQ(st.engine_non_finite, 1);
  EXPECT_EQ(st.engine_members, 11);
  Horizons h;
  h.horizon_s[0] = 0.5;
  Verdict v = MakeVerdict(scene, a, h, st);
  EXPECT_EQ(v.kind, "violates_model") << v.text;
  EXPECT_EQ(v.decided_by, "non_finite in 1 of its ensemble's members");
  EXPECT_NE(v.text.find("member 3: energy is +inf"), std::string::npos) << v.text;
  EXPECT_EQ(StatisticsJson(st)["engine_non_finite"], 1);

  members[5].status = RunStatus::kNonFinite;
  EXPECT_FALSE(members[5].valid());
  h.non_finite_members = 1;
  h.non_finite_detail = "member 5: theta1 is NaN at t = 0 s";
  v = MakeVerdict(scene, a, h, std::nullopt);
  EXPECT_EQ(v.kind, "reference_failed") << v.text;
  EXPECT_EQ(v.decided_by, "reference ensemble: 1 members non_finite");
}

INSTANTIATE_TEST_SUITE_P(BuiltEngines, EngineNonFinite,
                         ::testing::ValuesIn(testing_util::SuiteEngines()),
                         testing_util::EngineTestName);

}  // namespace
}  // namespace rockbench
