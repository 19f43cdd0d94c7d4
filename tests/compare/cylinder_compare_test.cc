// The comparison of a cylinder with its reference (compare/cylinder_compare.h): the tilt vector's
// components on the tilt's local tolerance, the fall, the perturbation members of the horizon
// (the transverse component and the cylinder's initial state perturbed) and the statistics on
// the tilt and the fall's azimuth.
#include "compare/cylinder_compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compare/verdict.h"
#include "reference/cylinder_run.h"
#include "run/tolerance.h"
#include "scene/body_kind.h"
#include "scene/scene.h"

namespace rockbench {
namespace {

using reference::cylinder::CylinderResult;
using reference::cylinder::SimulateCylinder;

// The shipped free wobbling's cylinder (D = 0.5 m, H = 1.5 m) leaning 0.1 rad, its lean turning
// at 1 rad/s, on a still base, for 4 s.
const char* kWobbling =
    "[[block]]\nshape = \"cylinder\"\ndiameter = 0.5\nheight = 1.5\ndensity = 2500\n"
    "[initial]\ntilt = [0.1]\nazimuth_rate = [1.0]\n[run]\nduration = 4\n"
    "output_interval = 0.005\n";

Scene WobblingScene(const std::vector<std::string>& overrides = {}) {
  return ParseScene(kWobbling, "wobbling.toml", overrides);
}

// The index of a cylinder's quantity in Sample::state.
size_t Index(const std::string& stem) {
  const std::vector<StateQuantity>& q = CylinderKind().state;
  for (size_t k = 0; k < q.size(); ++k) {
    if (q[k].stem == stem) return k;
  }
  ADD_FAILURE() << "no quantity " << stem;
  return 0;
}

// An "engine" whose run is the reference's history turned by `turn_rad` about the vertical.
EngineRun TurnedRun(const CylinderResult& ref, double turn_rad) {
  EngineRun run;
  run.engine = "turned";
  run.history = ref.history;
  const size_t tilt = Index("tilt"), az = Index("azimuth"), tx = Index("tilt_x"),
               ty = Index("tilt_y");
  for (Sample& s : run.history.samples) {
    s.state[az][0] += turn_rad;
    s.state[tx][0] = s.state[tilt][0] * std::cos(s.state[az][0]);
    s.state[ty][0] = s.state[tilt][0] * std::sin(s.state[az][0]);
  }
  run.outcome = RunOutcome(1);
  run.outcome.end_t_s = ref.summary.end_s;
  run.outcome.peak_theta_rad[0] = ref.summary.peak_tilt_rad;
  run.summary = nlohmann::json::object();
  return run;
}

TEST(CylinderCompareTest, TiltVectorAtInterpolatesAndHoldsTheEnd) {
  const CylinderResult ref = SimulateCylinder(WobblingScene(), GroundMotion{});
  const StateQuantityReader tx(ref.history, "tilt_x"), ty(ref.history, "tilt_y");
  const Sample& a = ref.history.samples[10];
  const Sample& b = ref.history.samples[11];
  // At a sample: its value, exactly.
  EXPECT_EQ(TiltVectorAt(ref.history, a.t_s).x_rad, tx(a, 1));
  // Between two: the straight line (a quarter of the way).
  const double t = a.t_s + 0.25 * (b.t_s - a.t_s);
  EXPECT_NEAR(TiltVectorAt(ref.history, t).y_rad, ty(a, 1) + 0.25 * (ty(b, 1) - ty(a, 1)), 1e-15);
  // After the end: the last sample.
  EXPECT_EQ(TiltVectorAt(ref.history, 99.0).y_rad, ty(ref.history.samples.back(), 1));
}

// A run turned by an angle delta about the vertical is off by the chord 2 tilt sin(delta / 2)
// at every sample: each component's error is at most the chord at the peak tilt, and the
// tolerance (10% of the 0.1 rad tilt: 0.01 rad) passes a turn whose chord is below it and stops
// one whose chord is above it.
TEST(CylinderCompareTest, ATurnedRunIsOffByItsChordOnTheTiltsTolerance) {
  const Scene scene = WobblingScene();
  const CylinderResult ref = SimulateCylinder(scene, GroundMotion{});
  const double tol = AngleTolerance_rad(scene, 1, ref.summary.peak_tilt_rad);
  ASSERT_NEAR(tol, 0.01, 1e-12);
  for (const double turn : {0.02, 0.3}) {
    const EngineAgreement a = CompareCylinderWithReference(scene, ref, TurnedRun(ref, turn));
    const double chord = 2.0 * ref.summary.peak_tilt_rad * std::sin(0.5 * turn);
    ASSERT_EQ(a.compared_angles().size(), 2u);
    const AngleAgreement& gx = a.angle(1);
    const AngleAgreement& gy = a.body(1).more_angles.at(0);
    EXPECT_EQ(gx.quantity, "tilt_x");
    EXPECT_EQ(gy.name, "tilt_y1");
    double largest = 0.0;
    for (const AngleAgreement* g : a.compared_angles()) {
      EXPECT_LE(g->max_abs_error_rad, chord * (1.0 + 1e-12)) << turn;
      largest = std::max(largest, g->max_abs_error_rad);
    }
    // The lean turns through 4 rad in 4 s: some sample puts most of the chord on one component
    // (the component's share is |sin| of an angle that sweeps past pi / 2).
    EXPECT_GT(largest, 0.9 * chord) << turn;
    const bool within = chord < tol;
    EXPECT_EQ(gx.within_tolerance && gy.within_tolerance, within) << turn << " chord " << chord;
    EXPECT_TRUE(a.overturn_agree);
    std::printf("measured: turn %.2f rad: chord %.4g rad, largest component error %.4g rad\n", turn,
                chord, largest);
  }
}

// The reference against its own solution: nothing to tell apart, and the pointwise verdict
// agrees; an engine that falls where the reference does not differs on the outcome.
TEST(CylinderCompareTest, VerdictOnTheSameMotionAndOnAFall) {
  const Scene scene = WobblingScene();
  const CylinderResult ref = SimulateCylinder(scene, GroundMotion{});
  EngineRun same = TurnedRun(ref, 0.0);
  EngineAgreement a = CompareCylinderWithReference(scene, ref, same);
  // (tilt cos(azimuth) recomputed: a rounding of the 0.1 rad tilt, 1e-15 at most.)
  EXPECT_LT(a.angle(1).max_abs_error_rad, 1e-15);
  EXPECT_TRUE(a.final_agree);
  Verdict v = MakeVerdict(scene, a, std::nullopt, std::nullopt);
  EXPECT_EQ(v.kind, "pointwise_only") << v.text;

  EngineRun falls = TurnedRun(ref, 0.0);
  falls.outcome.status = RunStatus::kOverturned;
  falls.outcome.overturned_block = 1;
  falls.outcome.overturn_t_s = 3.0;
  falls.summary["overturn"] = {{"t_s", 3.0}, {"azimuth_rad", 2.5}};
  a = CompareCylinderWithReference(scene, ref, falls);
  EXPECT_FALSE(a.overturn_agree);
  EXPECT_EQ(a.overturn_azimuth_engine_rad.value_or(0.0), 2.5);
  EXPECT_FALSE(a.overturn_azimuth_reference_rad.has_value());
  v = MakeVerdict(scene, a, std::nullopt, std::nullopt);
  EXPECT_EQ(v.kind, "pointwise_differs") << v.text;
  EXPECT_NE(v.text.find("block 1 overturns in the engine's run"), std::string::npos) << v.text;
}

// Member i's inputs: the transverse component's amplitude and the cylinder's initial tilt and
// rates are perturbed within the scene's sizes, the same way every time; the horizontal draw is
// the one a planar scene makes (the draws of planar scenes are unchanged).
TEST(CylinderCompareTest, MembersPerturbTheTransverseComponentAndTheInitialState) {
  const std::string motion =
      "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 2\n"
      "[base.transverse]\nkind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 2\n"
      "phase_deg = 90\n";
  const Scene scene = ParseScene(std::string(kWobbling) + motion, "w.toml", {});
  const GroundMotion nominal = GroundMotion::FromScene(scene);
  const Scene planar = ParseScene(
      "[[block]]\nwidth = 0.5\nheight = 1.5\ndensity = 2500\n[base.horizontal]\n"
      "kind = \"harmonic\"\namplitude_g = 0.1\nfrequency_hz = 2\n",
      "p.toml", {});
  for (int i = 0; i < 8; ++i) {
    const MemberInput in = PerturbedInput(scene, nominal, i);
    const MemberPerturbation& p = in.perturbation;
    const double a = scene.compare.amplitude_rel, r = scene.compare.initial_rel;
    EXPECT_LE(std::abs(p.transverse_factor - 1.0), a);
    EXPECT_NE(p.transverse_factor, 1.0);
    EXPECT_NEAR(in.motion.transverse_mps2(0.125),
                p.transverse_factor * nominal.transverse_mps2(0.125), 1e-15);
    EXPECT_LE(std::abs(p.tilt_factor - 1.0), r);
    EXPECT_DOUBLE_EQ(in.scene.initial.tilt_rad[0], 0.1 * p.tilt_factor);
    EXPECT_DOUBLE_EQ(in.scene.initial.azimuth_rate_radps[0], p.azimuth_rate_factor);
    EXPECT_EQ(in.scene.initial.azimuth_rad[0], 0.0);
    // Deterministic, and the horizontal draw a planar scene's.
    EXPECT_EQ(PerturbedInput(scene, nominal, i).perturbation.tilt_factor, p.tilt_factor);
    const MemberInput pi = PerturbedInput(planar, GroundMotion::FromScene(planar), i);
    EXPECT_EQ(pi.perturbation.horizontal_factor, p.horizontal_factor);
    EXPECT_EQ(pi.perturbation.transverse_factor, 1.0);
  }
}

// Members with nothing perturbed spread by nothing; a free wobble's spread grows with the size
// of its inputs' perturbation (its phase drifts with the wobble's rate): a smaller perturbation
// reaches the tolerance later.
TEST(CylinderCompareTest, TheHorizonComesLaterForASmallerPerturbation) {
  const auto horizon = [](const std::string& initial_rel) {
    const Scene scene = WobblingScene({"compare.initial_rel=" + initial_rel});
    const CylinderResult ref = SimulateCylinder(scene, GroundMotion{});
    return RunCylinderPerturbationMembers(
        scene, GroundMotion{}, ref, 8, AngleTolerance_rad(scene, 1, ref.summary.peak_tilt_rad), 1);
  };
  const ReferencePerturbationMembers none = horizon("0");
  EXPECT_EQ(none.stem, "tilt");
  EXPECT_EQ(none.max_spread_rad[0], 0.0);
  EXPECT_FALSE(none.horizon_s[0].has_value());
  const ReferencePerturbationMembers big = horizon("0.01"), small = horizon("0.002");
  ASSERT_TRUE(big.horizon_s[0].has_value());
  EXPECT_GT(small.horizon_s[0].value_or(1e9), *big.horizon_s[0]);
  std::printf("measured: horizon %.3f s at initial_rel 0.01, %s at 0.002\n", *big.horizon_s[0],
              small.horizon_s[0] ? std::to_string(*small.horizon_s[0]).c_str() : "none");
}

// The fall's azimuth is compared on the circle: falls on both sides of the azimuth pi are one
// direction; falls half a radian apart differ.
TEST(CylinderCompareTest, FallAzimuthsAreComparedOnTheCircle) {
  const auto members = [](double centre, int n) {
    std::vector<MemberOutcome> out(n);
    for (int i = 0; i < n; ++i) {
      out[i].member = i;
      out[i].overturned_block = 1;
      out[i].peak_rad[0] = 1.5707963267948966;
      out[i].overturn_t_s = 2.0 + 1e-3 * i;
      out[i].peak_t_s[0] = out[i].overturn_t_s;
      out[i].residual_rad[0] = out[i].peak_rad[0];
      // Alternately just below and just above the wrap at +-pi.
      out[i].overturn_azimuth_rad =
          std::remainder(centre + (i % 2 ? 1.0 : -1.0) * 1e-3 * (i + 1), 2.0 * M_PI);
    }
    return out;
  };
  const std::vector<double> tol = {0.03};
  const StatisticalComparison same =
      ComparePerturbationMembers(members(M_PI, 16), members(M_PI, 16), tol, 0.01, 0.05, "tilt");
  ASSERT_TRUE(same.available);
  bool found = false;
  for (const QuantityComparison& q : same.quantities) {
    if (q.key != "fall_azimuth1_rad") continue;
    found = true;
    EXPECT_GT(q.ks.p_value, 0.5);
    for (double v : q.reference) EXPECT_LT(std::abs(v), 0.02);
  }
  EXPECT_TRUE(found);
  EXPECT_TRUE(same.consistent);
  const StatisticalComparison turned = ComparePerturbationMembers(
      members(M_PI, 16), members(M_PI - 0.5, 16), tol, 0.01, 0.05, "tilt");
  EXPECT_FALSE(turned.consistent);
  EXPECT_EQ(turned.rejected.front(), "fall_azimuth1_rad");
}

}  // namespace
}  // namespace rockbench
