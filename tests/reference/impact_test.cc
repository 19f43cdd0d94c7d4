// Impact laws (thesis chapter 5): conservation of the angular momenta each law claims, no
// energy gain over a sweep of geometries, the squat-block case, the thesis's first choice and
// the rest rule. Housner's coefficient (eqs. 3.8, 3.9) and the closed forms 5.29, 5.31, 5.34
// and 5.36 of the stack's impacts (reference/benchmarks) are checked in closed_forms_test.cc.
#include "reference/thesis/impact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "reference/benchmarks/closed_forms.h"
#include "reference/thesis/kinematics.h"

namespace rockbench::reference {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Case {
  Mode before;
  ImpactKind kind;
};

// A state of `before` exactly at its impact configuration, with rates that close the gap.
State ImpactState(Mode before, ImpactKind kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ang(0.02, 0.5), rate(0.05, 2.0);
  const Contacts c = ContactsOf(before);
  const double sg = c.ground == Contact::kRight ? 1.0 : -1.0;
  const double si = c.interface == Contact::kRight ? 1.0 : -1.0;
  State s;
  if (kind == ImpactKind::kGround) {
    s.theta1 = 0.0;
    s.omega1 = -sg * rate(rng);  // falling back onto the ground
    if (c.interface == Contact::kFace) {
      s.theta2 = 0.0;
      s.omega2 = s.omega1;
    } else {
      s.theta2 = si * ang(rng);
      s.omega2 = std::uniform_real_distribution<double>(-2.0, 2.0)(rng);
    }
  } else {
    if (c.ground == Contact::kFace) {
      s.theta1 = s.omega1 = 0.0;
      s.theta2 = 0.0;
      s.omega2 = -si * rate(rng);
    } else {
      s.theta1 = sg * ang(rng);
      s.theta2 = s.theta1;
      s.omega1 = std::uniform_real_distribution<double>(-2.0, 2.0)(rng);
      s.omega2 = s.omega1 - si * rate(rng);  // block 2 closing onto block 1
    }
  }
  return s;
}

Geometry RandomGeometry(std::mt19937_64& rng, double mass_ratio_lo = 0.01,
                        double mass_ratio_hi = 100.0) {
  std::uniform_real_distribution<double> slender(0.5, 10.0), width(0.3, 2.0);
  std::uniform_real_distribution<double> log_ratio(std::log(mass_ratio_lo),
                                                   std::log(mass_ratio_hi));
  const double B1 = width(rng), H1 = B1 * slender(rng);
  const double B2 = B1 * std::uniform_real_distribution<double>(0.1, 1.0)(rng);
  const double H2 = B2 * slender(rng);
  const double m1 = 1000.0 * B1 * H1;
  return MakeGeometry(B1, H1, m1, B2, H2, m1 * std::exp(log_ratio(rng)));
}

const Case kCases[] = {
    {Mode::k1a, ImpactKind::kGround},    {Mode::k1b, ImpactKind::kGround},
    {Mode::k2a, ImpactKind::kGround},    {Mode::k2b, ImpactKind::kGround},
    {Mode::k3a, ImpactKind::kGround},    {Mode::k3b, ImpactKind::kGround},
    {Mode::k1a, ImpactKind::kInterface}, {Mode::k1b, ImpactKind::kInterface},
    {Mode::k2a, ImpactKind::kInterface}, {Mode::k2b, ImpactKind::kInterface},
    {Mode::k4a, ImpactKind::kInterface}, {Mode::k4b, ImpactKind::kInterface},
};

// Each outcome conserves the angular momentum of the whole system about its ground pivot (when
// block 1 rocks on a corner after the impact) and of block 2 about its pivot on block 1 (when
// block 2 rocks on a corner): the laws of eqs. 5.12-5.13, 5.15-5.16, 5.20-5.21, 5.23-5.24,
// 5.27-5.28, 5.32-5.33, and their one-degree-of-freedom fallbacks 5.18, 5.26, 5.30, 5.35.
TEST(ImpactTest, EachLawConservesTheAngularMomentaItClaims) {
  std::mt19937_64 rng(7);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Geometry geo = RandomGeometry(rng);
    for (const Case& k : kCases) {
      const State pre = ImpactState(k.before, k.kind, rng);
      for (Mode after : ImpactCandidates(k.before, k.kind, true)) {
        const State post = PostImpactState(geo, k.before, pre, after);
        const Contacts c = ContactsOf(after);
        const Chain ch = EvaluateChain(geo, after, pre);
        // Scale: |h| of the moving parts before the impact.
        const double scale = std::abs(AngularMomentum(geo, k.before, pre, ch.P1, -1)) +
                             std::abs(AngularMomentum(geo, k.before, pre, ch.Q2, 1)) + 1e-300;
        const double tol = 256 * kEps * scale;
        if (c.ground != Contact::kFace) {
          EXPECT_NEAR(AngularMomentum(geo, after, post, ch.P1, -1),
                      AngularMomentum(geo, k.before, pre, ch.P1, -1), tol)
              << ModeName(k.before) << " -> " << ModeName(after) << " system about O1";
          ++checked;
        }
        if (c.interface != Contact::kFace) {
          EXPECT_NEAR(AngularMomentum(geo, after, post, ch.Q2, 1),
                      AngularMomentum(geo, k.before, pre, ch.Q2, 1), tol)
              << ModeName(k.before) << " -> " << ModeName(after) << " block 2 about O2";
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 5000);
}

// A perfectly plastic impact projects the velocities onto the post-impact mode's motions in
// the kinetic-energy metric, so it can only lose energy: over mass ratios 0.01 to 100 and
// slenderness 0.5 to 10, no outcome (admissible or not) gains more than rounding.
TEST(ImpactTest, NoImpactAddsEnergy) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    const Geometry geo = RandomGeometry(rng);
    for (const Case& k : kCases) {
      const State pre = ImpactState(k.before, k.kind, rng);
      const ImpactResult res = ResolveImpact(geo, k.before, pre, k.kind, 0.0);
      const double kinetic =
          res.energy_before_j - Energy(geo, k.before, {pre.theta1, pre.theta2, 0.0, 0.0});
      ASSERT_GT(kinetic, 0.0);
      // Energies of ~m g h with kinetic parts ~kinetic: rounding of ~1e3 ulps of the total.
      const double tol = 1e3 * kEps * std::abs(res.energy_before_j);
      for (const ImpactOutcome& o : res.candidates) {
        EXPECT_LE(o.energy_after_j - res.energy_before_j, tol)
            << ModeName(k.before) << " -> " << ModeName(o.mode) << " trial " << trial;
      }
    }
  }
}

// A squat block (H/B < 1/sqrt(2)) has a negative Housner coefficient: rocking on about the
// other corner would need the block to keep rotating into the ground. The model stops it: the
// face lands flat, with compressive impulses at both corners, and all its kinetic energy lost.
TEST(ImpactTest, SquatBlockComesToRest) {
  for (double slender : {0.3, 0.5, 0.7}) {
    const double B = 1.0, H = B * slender;
    const Geometry geo = MakeGeometry(B, H, 2500.0 * B * H, 0.0, 0.0, 0.0);
    ASSERT_LT(benchmarks::HousnerRestitution(geo.block1.theta_c), 0.0);
    const State pre{0.0, 0.0, -0.3, -0.3};
    const ImpactResult res = ResolveImpact(geo, Mode::k3a, pre, ImpactKind::kGround, 0.0);
    EXPECT_FALSE(res.candidates[0].velocity_admissible);  // 3b would move into the ground
    EXPECT_EQ(res.chosen.mode, Mode::kRest);
    EXPECT_TRUE(res.admissible);
    EXPECT_GE(res.chosen.min_normal_impulse, 0.0);
    EXPECT_EQ(res.chosen.state.omega1, 0.0);
  }
  // Just above the limit, the block rocks on.
  const double H = 1.0 / std::sqrt(2.0) * 1.01;
  const Geometry geo = MakeGeometry(1.0, H, 2500.0 * H, 0.0, 0.0, 0.0);
  const ImpactResult res =
      ResolveImpact(geo, Mode::k3a, {0.0, 0.0, -0.3, -0.3}, ImpactKind::kGround, 0.0);
  EXPECT_EQ(res.chosen.mode, Mode::k3b);
}

// The thesis's choices on its own example geometry: 3a ground impact -> 1b (fig. 5.5), with
// admissible velocities and impulses.
TEST(ImpactTest, ThesisExampleFirstImpactGoesTo1b) {
  const Geometry geo = MakeGeometry(1.25, 1.25, 3906.25, 1.0, 2.5, 6250.0);
  const ImpactResult res =
      ResolveImpact(geo, Mode::k3a, {0.0, 0.0, -0.5, -0.5}, ImpactKind::kGround, 0.0);
  EXPECT_EQ(res.chosen.mode, Mode::k1b);
  EXPECT_TRUE(res.admissible);
  // Block 2 leaves block 1 rotating faster (the thesis: "the angular velocity of block 2
  // increases during the first impact").
  EXPECT_LT(res.chosen.state.omega2, res.chosen.state.omega1);
}

// The rest rule: an opening rate below rest_rate_rel sqrt(g / R) keeps the contact closed,
// with R the distance from the pivot to the mass centre of what settles: the block (or the
// stack) at the ground, block 2 at the interface. Just above and just below the threshold
// (Housner's e = 0.912 for H/B = 4 turns the pre-impact rate into the post-impact one).
TEST(ImpactTest, RestRuleSettlesImpactsBelowTheRelativeRate) {
  const Geometry geo = MakeGeometry(1.0, 4.0, 10000.0, 0.0, 0.0, 0.0);
  const double rel = 1e-4;
  const double thr = rel * std::sqrt(geo.g / geo.block1.r);
  EXPECT_DOUBLE_EQ(RestRate(geo, ImpactKind::kGround, rel), thr);
  const double e = benchmarks::HousnerRestitution(geo.block1.theta_c);
  for (const double f : {1.01, 0.99}) {
    const double w = -f * thr / e;  // post-impact rate f * thr
    const ImpactResult r =
        ResolveImpact(geo, Mode::k3a, {0.0, 0.0, w, w}, ImpactKind::kGround, rel);
    EXPECT_EQ(r.chosen.mode, f > 1 ? Mode::k3b : Mode::kRest) << f;
    EXPECT_EQ(r.settled, f < 1) << f;
  }
  // Zero: never settles.
  EXPECT_EQ(ResolveImpact(geo, Mode::k3a, {0.0, 0.0, -1e-12, -1e-12}, ImpactKind::kGround, 0.0)
                .chosen.mode,
            Mode::k3b);
  // Two blocks: the ground uses the stack's R, the interface block 2's r.
  const Geometry two = MakeGeometry(1.25, 1.25, 3906.25, 1.0, 2.5, 6250.0);
  EXPECT_DOUBLE_EQ(RestRate(two, ImpactKind::kGround, rel), rel * std::sqrt(two.g / two.R));
  EXPECT_DOUBLE_EQ(RestRate(two, ImpactKind::kInterface, rel),
                   rel * std::sqrt(two.g / two.block2.r));
}

// The rule is the same at every size: scaled by k in length (masses by k^3), with rates
// divided by sqrt(k), an impact settles or not exactly as at k = 1, for rates either side of
// the threshold and every impact case of the thesis's stack.
TEST(ImpactTest, RestRuleIsTheSameAtEverySize) {
  const double rel = 1e-4;
  const Case cases[] = {{Mode::k3a, ImpactKind::kGround},    {Mode::k1a, ImpactKind::kGround},
                        {Mode::k2a, ImpactKind::kGround},    {Mode::k1a, ImpactKind::kInterface},
                        {Mode::k2a, ImpactKind::kInterface}, {Mode::k4a, ImpactKind::kInterface}};
  std::mt19937_64 rng(7);
  int settled = 0, total = 0;
  for (const Case& c : cases) {
    for (int trial = 0; trial < 200; ++trial) {
      State s = ImpactState(c.before, c.kind, rng);
      // Rates near the threshold (2.3e-4 rad/s at the ground, 2.7e-4 at the interface): the
      // rates of ImpactState (0.05 to 2 rad/s) times e^-10 .. e^-5, 2e-6 to 1.3e-2 rad/s.
      const double shrink = std::exp(std::uniform_real_distribution<double>(-10.0, -5.0)(rng));
      s.omega1 *= shrink;
      s.omega2 *= shrink;
      const Geometry g1 = MakeGeometry(1.25, 1.25, 3906.25, 1.0, 2.5, 6250.0);
      const ImpactResult r1 = ResolveImpact(g1, c.before, s, c.kind, rel);
      for (const double k : {0.01, 100.0}) {
        const Geometry gk = MakeGeometry(1.25 * k, 1.25 * k, 3906.25 * k * k * k, 1.0 * k, 2.5 * k,
                                         6250.0 * k * k * k);
        State sk = s;
        sk.omega1 /= std::sqrt(k);
        sk.omega2 /= std::sqrt(k);
        const ImpactResult rk = ResolveImpact(gk, c.before, sk, c.kind, rel);
        EXPECT_EQ(rk.chosen.mode, r1.chosen.mode) << k;
        EXPECT_EQ(rk.settled, r1.settled) << k;
      }
      settled += r1.settled;
      ++total;
    }
  }
  // Both outcomes occur among the trials (the rates straddle the threshold).
  EXPECT_GT(settled, total / 10);
  EXPECT_LT(settled, total - total / 10);
}

}  // namespace
}  // namespace rockbench::reference
