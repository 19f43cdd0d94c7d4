// The closed forms of reference/benchmarks, each against an independent check: a second
// derivation (the elliptic integral against the quadrature, Housner's e against the angular
// momentum of a general body, a stack of two equal blocks or a column of N against one tall
// block, a column of one or two blocks against Housner's block and the locked stack), a limit
// (small angles, a vanishing upper block), or the reference's own runs and impact laws (event
// times, rates and thresholds, which the reference computes by other means: integration of
// the equations of motion, generalized momenta in the base frame). Every bound is derived in
// the comment above it. simulate_test.cc, impact_test.cc and pulse_test.cc use the same forms
// to check the reference's integrators, impact choices and pulse thresholds.
#include "reference/benchmarks/closed_forms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "common/rectangular_pulse.h"
#include "common/thesis_scene.h"
#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/impact.h"
#include "reference/thesis/kinematics.h"
#include "scene/scene.h"

namespace rockbench::reference {
namespace {

namespace bm = benchmarks;
constexpr double kEps = std::numeric_limits<double>::epsilon();

std::vector<Event> Impacts(const History& h) {
  std::vector<Event> out;
  for (const Event& e : h.events) {
    if (e.kind == "ground_impact" || e.kind == "interface_impact") out.push_back(e);
  }
  return out;
}

// A single block of full width B and height H (m), 2500 kg/m^3, 1 m deep, from rest at theta0.
Scene OneBlock(double B, double H, double theta0_rad, double duration_s) {
  Scene sc;
  sc.blocks = {{B, H, 1.0, 2500.0 * B * H, 2500.0}};
  sc.initial.theta_rad[0] = theta0_rad;
  sc.run.duration_s = duration_s;
  sc.model.rtol = 1e-12;
  sc.model.atol = 1e-14;
  return sc;
}

// --- 1. Housner's restitution ----------------------------------------------------------------

// e = 1 - 2 m b^2 / I_O of a body with a rectangle's I_O = (4/3) m R^2 is Housner's
// 1 - 1.5 sin^2(alpha): two evaluations of O(1) terms with a few roundings each, so they agree
// to a few ulps (bound 8 eps, absolute: e is O(1)). Exact values: H/B = 2 (sin^2 = 1/5) gives
// 0.7, H/B = 4 (sin^2 = 1/17) gives 1 - 1.5 / 17, H/B = 1/sqrt(2) (sin^2 = 2/3) gives 0.
TEST(ClosedFormsTest, HousnerRestitutionIsTheCornerImpactOfARectangle) {
  for (const double slender : {0.5, 1.0 / std::sqrt(2.0), 1.0, 2.0, 4.0, 10.0, 50.0}) {
    const bm::RockingBody body = bm::RectangularBlock(1.0, slender, 2500.0 * slender, 9.81);
    EXPECT_NEAR(bm::CornerImpactRestitution(body), bm::HousnerRestitution(body.alpha_rad()),
                8 * kEps)
        << "H/B " << slender;
  }
  EXPECT_NEAR(bm::HousnerRestitution(std::atan(0.5)), 0.7, 4 * kEps);
  EXPECT_NEAR(bm::HousnerRestitution(std::atan(0.25)), 1.0 - 1.5 / 17.0, 4 * kEps);
  EXPECT_NEAR(bm::HousnerRestitution(std::atan(std::sqrt(2.0))), 0.0, 4 * kEps);
}

// The reference's impact (generalized momentum of the post-impact mode, in the base frame)
// gives the rate ratio e, and keeps the fraction e^2 of the kinetic energy (before the impact
// the block turns about one corner, after it about the other, with the same I_O). The rate
// ratio is the ratio of two momenta of O(1) terms: 16 eps. The kinetic energies are total
// energies minus the potential m g h at theta = 0, so their ratio carries the rounding of the
// totals, eps E / K: bound 64 eps E / K.
TEST(ClosedFormsTest, ReferenceImpactHasHousnersRestitutionAndEnergyLoss) {
  for (const double slender : {0.8, 1.0, 2.0, 4.0, 10.0}) {
    const double B = 1.0, H = B * slender, m = 2500.0 * B * H;
    const Geometry geo = MakeGeometry(B, H, m, 0.0, 0.0, 0.0);
    const double e = bm::CornerImpactRestitution(bm::RectangularBlock(B, H, m, geo.g));
    const State pre{0.0, 0.0, -2.0, -2.0};
    const ImpactResult res = ResolveImpact(geo, Mode::k3a, pre, ImpactKind::kGround, 0.0);
    ASSERT_EQ(res.chosen.mode, Mode::k3b) << "H/B " << slender;
    EXPECT_TRUE(res.admissible) << "H/B " << slender;
    EXPECT_NEAR(res.chosen.state.omega1 / pre.omega1, e, 16 * kEps) << "H/B " << slender;
    const double V = m * geo.g * 0.5 * H;
    const double K_before = res.energy_before_j - V, K_after = res.chosen.energy_after_j - V;
    EXPECT_NEAR(K_after / K_before, e * e, 64 * kEps * res.energy_before_j / K_before)
        << "H/B " << slender;
  }
}

// --- 2. Free rocking -------------------------------------------------------------------------

// The quadrature against the elliptic integral: two exact expressions of the same time,
// evaluated by different means (adaptive Gauss-Kronrod on the smoothed integrand; Carlson's
// R_F). The elliptic route evaluates 1 - k^2 sin^2(beta1) with k -> 1 and beta1 -> pi/2 as the
// release nears the top, a cancellation of relative size (1 - theta0 / alpha)^2 (measured
// 0.1 eps / (1 - theta0 / alpha)^2): bound 1e-14 + eps / (1 - theta0 / alpha)^2, relative.
TEST(ClosedFormsTest, FirstImpactTimeQuadratureIsTheEllipticIntegral) {
  for (const double alpha : {0.01, 0.1, std::atan(0.25), 0.6, 1.0, 1.4}) {
    for (const double f : {1e-6, 1e-3, 0.1, 0.5, 0.9, 0.999}) {
      const bm::RockingBody body{1.0, std::sin(alpha), std::cos(alpha), 4.0 / 3.0, 9.81};
      const double tq = bm::FirstImpactTime_s(body, f * alpha);
      const double te = bm::FirstImpactTimeElliptic_s(body, f * alpha);
      EXPECT_NEAR(tq / te, 1.0, 1e-14 + kEps / ((1.0 - f) * (1.0 - f)))
          << "alpha " << alpha << " theta0 / alpha " << f;
    }
  }
}

// Housner's linearised time is the small-angle limit of the exact one, with the leading
// correction derived in closed_forms.cc: t / t_H - 1 = c alpha^2 + O(alpha^4),
//   c = (phi0 / alpha)^2 / 16 + sqrt(1 - (phi0 / alpha)^2) / (48 acosh(alpha / phi0)),
// phi0 = alpha - theta0. The next term of the same expansion (the O(phi^4) terms of
// 2 (cos phi0 - cos phi) / (phi^2 - phi0^2) = 1 - S1 / 12 + S2 / 360 - ..., S1 = phi^2 + phi0^2
// <= 2 alpha^2, S2 = phi^4 + phi^2 phi0^2 + phi0^4 <= 3 alpha^4, in (1 - y)^(-1/2) = 1 + y / 2
// + 3 y^2 / 8) is 3 S1^2 / 1152 - S2 / 720, at most 0.0104 alpha^4 in size: so |(t / t_H - 1)
// / alpha^2 - c| <= 0.0104 alpha^2 plus higher orders; bound 0.011 alpha^2 for alpha <= 0.25
// (measured 0.0063 alpha^2 at theta0 -> 0, where the bound's two terms are 0.0104 and 0.0042).
TEST(ClosedFormsTest, FirstImpactTimeTendsToHousnersLinearisedTime) {
  for (const double alpha : {0.25, 0.1, 0.05, 0.02}) {
    for (const double f : {1e-3, 0.1, 0.5, 0.9, 0.999}) {
      const bm::RockingBody body = bm::RectangularBlock(std::tan(alpha), 1.0, 1000.0, 9.81);
      const double theta0 = f * body.alpha_rad(), a = body.alpha_rad(), u = 1.0 - f;
      const double c = u * u / 16.0 + std::sqrt(1.0 - u * u) / (48.0 * std::acosh(1.0 / u));
      const double t = bm::FirstImpactTime_s(body, theta0);
      const double t_h = bm::HousnerFirstImpactTime_s(body, theta0);
      EXPECT_NEAR((t / t_h - 1.0) / (a * a), c, 0.011 * a * a)
          << "alpha " << alpha << " theta0 / alpha " << f;
    }
  }
}

// The other linearised forms are small-angle limits of the exact ones too. The thesis's
// first-impact time (3.43) errs by O(alpha^2) relative, like Housner's: halving alpha quarters
// the error (ratio 4, to within the next order's O(alpha^2) of it: 4 +- 10% at alpha <= 0.1).
// Housner's amplitude decay errs by O(alpha^4) only: the energy's linearisation error, a factor
// 1 - alpha^2 (1 + (1 - theta / alpha)^2) / 12 on each side of cos(alpha - theta_n) -
// cos(alpha) = e^(2n) (cos(alpha - theta0) - cos(alpha)), cancels but for the change of
// amplitude, itself O(alpha^2) (1 - e ~ 1.5 alpha^2): halving alpha divides the error by 16
// (+- 10% at alpha <= 0.05).
TEST(ClosedFormsTest, LinearisedFormsHaveTheirOrders) {
  auto body_of = [](double alpha) {
    return bm::RectangularBlock(std::tan(alpha), 1.0, 1000.0, 9.81);
  };
  auto time_errors = [&](double alpha) {
    const bm::RockingBody body = body_of(alpha);
    const double theta0 = 0.5 * alpha, t = bm::FirstImpactTime_s(body, theta0);
    return std::vector<double>{std::abs(bm::LinearizedFirstImpactTime_s(body, theta0) / t - 1.0),
                               std::abs(bm::HousnerFirstImpactTime_s(body, theta0) / t - 1.0)};
  };
  auto amplitude_errors = [&](double alpha) {
    const bm::RockingBody body = body_of(alpha);
    std::vector<double> err;
    for (const int n : {1, 3}) {
      const double exact = bm::FreeRockingAmplitudeAfterImpacts_rad(body, 0.5 * alpha, n);
      err.push_back(
          std::abs(bm::HousnerAmplitudeAfterImpacts_rad(body, 0.5 * alpha, n) / exact - 1.0));
    }
    return err;
  };
  for (const auto& [errors, alpha, ratio] :
       {std::tuple{std::function<std::vector<double>(double)>(time_errors), 0.1, 4.0},
        std::tuple{std::function<std::vector<double>(double)>(amplitude_errors), 0.05, 16.0}}) {
    const std::vector<double> e1 = errors(alpha), e2 = errors(0.5 * alpha);
    for (size_t i = 0; i < e1.size(); ++i) {
      EXPECT_GT(e1[i], 1e-8) << i;  // not zero by accident: a real error of that order
      EXPECT_NEAR(e1[i] / e2[i], ratio, 0.1 * ratio)
          << "ratio " << ratio << ", form " << i << ": " << e1[i] << " / " << e2[i];
    }
  }
}

// The reference's free rocking of Housner's block (B = 1 m, H = 4 m) from theta_c / 2: the
// first impact at the quadrature time, the rate before it from energy, the ratio across it e,
// the next impact one exact half cycle later, and the apex between them (the middle of the
// symmetric arc) the amplitude after one impact. rtol 1e-12: event times to ~1e-11 relative,
// asked 1e-9 (as in simulate_test.cc); rates at the events the same; the rate ratio is formed
// by the impact law from the located state, 16 eps as above; the apex from the dense output,
// 1e-10 rad.
TEST(ClosedFormsTest, ReferenceFreeRockingFollowsTheExactForms) {
  Scene sc = OneBlock(1.0, 4.0, 0.0, 3.0);
  const Geometry geo = MakeGeometry(sc);
  const bm::RockingBody body = bm::RectangularBlock(1.0, 4.0, sc.blocks[0].mass_kg, geo.g);
  const double theta0 = 0.5 * body.alpha_rad();
  sc.initial.theta_rad[0] = theta0;
  const Result res = Simulate(sc, GroundMotion{});
  const std::vector<Event> imp = Impacts(res.history);
  ASSERT_GE(imp.size(), 3u);
  const double t1 = bm::FirstImpactTime_s(body, theta0);
  EXPECT_NEAR(imp[0].t_s, t1, 1e-9 * t1);
  const double w1 = bm::FreeRockingImpactRate_radps(body, theta0);
  EXPECT_NEAR(std::abs(imp[0].omega_before_radps[0]), w1, 1e-9 * w1);
  EXPECT_NEAR(imp[0].omega_after_radps[0] / imp[0].omega_before_radps[0],
              bm::CornerImpactRestitution(body), 16 * kEps);
  const double half = bm::FreeRockingHalfCycle_s(body, std::abs(imp[0].omega_after_radps[0]));
  EXPECT_NEAR(imp[1].t_s - imp[0].t_s, half, 1e-9 * half);
  const double apex = std::abs(res.trajectory.At(imp[0].t_s + 0.5 * half).theta_rad[0]);
  EXPECT_NEAR(apex, bm::FreeRockingAmplitudeAfterImpacts_rad(body, theta0, 1), 1e-10);
}

// The thesis's stack (section 6.3.1) released from 0.15 rad, locked (mode 3a) until its first
// impact as the thesis narrates it (transition checks off: with them block 2 lifts off at
// 0.36 s, simulate_test.cc ThesisExample631): the impact comes at the LockedStack's quadrature
// time and energy rate (the stack's M, R, I_O and alpha, built here from the two blocks'
// properties, not the reference's), and the stack leaves in 1b with the rates of eq. 5.29
// (bounds as for the single block; the ratios: 32 eps kappa L (1 + |u|) < 1e-12 for this
// stack, as in ReferenceImpactLawsAreTheThesisClosedForms).
TEST(ClosedFormsTest, ReferenceStackFirstImpactFollowsTheLockedStackForms) {
  Scene sc = testing_util::ThesisFreeRockingStack(1.5);
  sc.model.check_transitions = false;
  const Geometry geo = MakeGeometry(sc);
  const bm::RockingBody stack = bm::LockedStack(geo.block1, geo.block2, geo.g);
  const Result res = Simulate(sc, GroundMotion{});
  const std::vector<Event> imp = Impacts(res.history);
  ASSERT_FALSE(imp.empty());
  ASSERT_EQ(ModeOfConfiguration(imp[0].mode_before), Mode::k3a);
  const double t1 = bm::FirstImpactTime_s(stack, sc.initial.theta_rad[0]);
  EXPECT_NEAR(imp[0].t_s, t1, 1e-9 * t1);
  const double w = bm::FreeRockingImpactRate_radps(stack, sc.initial.theta_rad[0]);
  EXPECT_NEAR(std::abs(imp[0].omega_before_radps[0]), w, 1e-9 * w);
  ASSERT_TRUE(bm::ThesisOutcomeAfter3aIs1b(geo.block1, geo.block2));
  EXPECT_EQ(ModeOfConfiguration(imp[0].mode_after), Mode::k1b);
  const bm::RateRatios r = bm::StackGroundImpact3aTo1b(geo.block1, geo.block2);
  EXPECT_NEAR(imp[0].omega_after_radps[0] / imp[0].omega_before_radps[0], r.theta1, 1e-12);
  EXPECT_NEAR(imp[0].omega_after_radps[1] / imp[0].omega_before_radps[0], r.theta2, 1e-12);
}

// The reference's equations = "linearized" are the thesis's eq. 3.39 for one block: first
// impact at LinearizedFirstImpactTime_s (eq. 3.43, a quarter of 3.44's period), the next one
// LinearizedHalfCycle_s later. Event times to 1e-9 relative, as above.
TEST(ClosedFormsTest, ReferenceLinearizedModelFollowsTheLinearisedForms) {
  Scene sc = OneBlock(1.0, 4.0, 0.0, 3.0);
  sc.model.equations = Equations::kLinearized;
  const Geometry geo = MakeGeometry(sc);
  const bm::RockingBody body = bm::RectangularBlock(geo.block1, geo.g);
  sc.initial.theta_rad[0] = 0.5 * body.alpha_rad();
  const std::vector<Event> imp = Impacts(Simulate(sc, GroundMotion{}).history);
  ASSERT_GE(imp.size(), 2u);
  const double t1 = bm::LinearizedFirstImpactTime_s(body, sc.initial.theta_rad[0]);
  EXPECT_NEAR(imp[0].t_s, t1, 1e-9 * t1);
  const double half = bm::LinearizedHalfCycle_s(body, std::abs(imp[0].omega_after_radps[0]));
  EXPECT_NEAR(imp[1].t_s - imp[0].t_s, half, 1e-9 * half);
}

// --- 3. Rectangular pulse --------------------------------------------------------------------

// A slender block B / H = ratio, H = 4 m, in standard gravity (amplitude_g is a_p / g
// exactly), 15 s; overturned once past 0.5 rad (a free block beyond its top cannot come back).
Scene SlenderBlock(double ratio) {
  Scene s = OneBlock(4.0 * ratio, 4.0, 0.0, 15.0);
  s.run.gravity_mps2 = kStandardGravity_mps2;
  s.model.overturn_rad = 0.5;
  return s;
}

// The thesis-linearised threshold is the linearized model's exactly: a pair of runs 1e-7 either
// side of it brackets it. Near the threshold the block lingers at the top for (1/q) ln(1 /
// 1e-7) = 8.4 s at most (q >= 1.9 rad/s here), inside the 15 s run; the integrator's rtol
// 1e-12 moves the threshold by far less (pulse_test.cc locates it to 1e-8).
// The exact (nonlinear) threshold differs from either closed form by the linearisation's
// error, second order in the angles: over theta in [0, alpha] the forcing p^2 (a_p / g
// cos(alpha - theta) - sin(alpha - theta)) differs from its linear form by at most theta
// tan(alpha) <= alpha^2 relative in the lever arm, and by sin(alpha) theta^2 / 2 <= sin(alpha)
// alpha^2 / 2 in the restoring moment, against terms of size sin(alpha) (a_p / g ~ tan
// alpha): so the exact threshold is within about alpha^2 (relative) of the thesis's form, and of
// Housner's, which differs from it by tan(alpha) / alpha - 1 ~ alpha^2 / 3 and q / p - 1 ~
// -alpha^2 / 4. Bisected to 1e-7 (measured 0.149 alpha^2 below the thesis's form at q t_d =
// 0.5, 0.094 alpha^2 at 2). Being second order, (exact / linearised - 1) / alpha^2 is the same
// at alpha = 0.1 and 0.05 but for the next order, O(alpha^2) of it: bound 0.01 (alpha^2 at
// alpha = 0.1; measured 3e-4).
TEST(ClosedFormsTest, RectangularPulseThresholdBracketsTheReference) {
  std::vector<double> scaled_gap[2];  // (exact / linearised - 1) / alpha^2, per B/H, per q t_d
  for (int k = 0; k < 2; ++k) {
    const double ratio = k == 0 ? 0.1 : 0.05;
    const Scene s = SlenderBlock(ratio);
    const bm::RockingBody body = bm::RectangularBlock(MakeGeometry(s).block1, s.run.gravity_mps2);
    const double a = body.alpha_rad();
    const double q = body.p_radps() * std::sqrt(std::cos(a));
    for (const double qt : {0.5, 2.0}) {
      SCOPED_TRACE("B/H " + std::to_string(ratio) + ", q t_d " + std::to_string(qt));
      const double td = qt / q;
      const double lin = bm::RectangularPulseOverturningAcceleration_mps2(body, td) / body.g_mps2;
      const double housner =
          bm::HousnerRectangularPulseOverturningAcceleration_mps2(body, td) / body.g_mps2;
      EXPECT_FALSE(RectangularPulseOverturns(s, lin * (1 - 1e-7), td, Equations::kLinearized));
      EXPECT_TRUE(RectangularPulseOverturns(s, lin * (1 + 1e-7), td, Equations::kLinearized));
      double lo = lin * (1 - a * a), hi = lin * (1 + a * a);
      ASSERT_FALSE(RectangularPulseOverturns(s, lo, td, Equations::kNonlinear));
      ASSERT_TRUE(RectangularPulseOverturns(s, hi, td, Equations::kNonlinear));
      while (hi - lo > 1e-7 * hi) {
        const double mid = 0.5 * (lo + hi);
        (RectangularPulseOverturns(s, mid, td, Equations::kNonlinear) ? hi : lo) = mid;
      }
      EXPECT_NEAR(hi / housner, 1.0, a * a);
      scaled_gap[k].push_back((hi / lin - 1.0) / (a * a));
      RecordProperty("exact_over_linearised_minus_1_over_alpha2_bh" + std::to_string(ratio) +
                         "_qt" + std::to_string(qt),
                     std::to_string(scaled_gap[k].back()));
    }
  }
  for (size_t i = 0; i < scaled_gap[0].size(); ++i) {
    EXPECT_NEAR(scaled_gap[0][i], scaled_gap[1][i], 0.01) << "q t_d #" << i;
  }
}

// The closed form's limits: a long pulse needs the static threshold g tan(alpha); a short one
// the velocity step a_p t_d -> g tan(alpha) / q that carries the linear body to its top (both
// to the next order of the expansion: exp(-q t_d) and q t_d / 2 relative).
TEST(ClosedFormsTest, RectangularPulseThresholdLimits) {
  const bm::RockingBody body = bm::RectangularBlock(0.4, 4.0, 4000.0, 9.81);
  const double a = body.alpha_rad(), q = body.p_radps() * std::sqrt(std::cos(a));
  const double g_tan = body.g_mps2 * std::tan(a);
  EXPECT_NEAR(bm::RectangularPulseOverturningAcceleration_mps2(body, 40.0 / q) / g_tan, 1.0,
              2 * std::exp(-40.0));
  const double td = 1e-6 / q;
  EXPECT_NEAR(bm::RectangularPulseOverturningAcceleration_mps2(body, td) * td / (g_tan / q), 1.0,
              1e-6);
}

// --- 4. The two-block impacts ----------------------------------------------------------------

// Two blocks of the same width and density locked together are one block of height H1 + H2:
// the stack's mass, mass-centre height, I_O, p and alpha, and its 3a -> 3b coefficient, are
// that block's (and Housner's e of it). Sums of a few products: 8 eps relative.
TEST(ClosedFormsTest, LockedStackOfEqualWidthsIsOneTallBlock) {
  for (const auto& [B, H1, H2] :
       {std::tuple{1.0, 1.0, 3.0}, std::tuple{1.25, 1.25, 2.5}, std::tuple{0.4, 3.0, 0.5}}) {
    const double rho = 2500.0;
    const BlockProps p1 = MakeBlockProps(B, H1, rho * B * H1),
                     p2 = MakeBlockProps(B, H2, rho * B * H2);
    const bm::RockingBody stack = bm::LockedStack(p1, p2, 9.81);
    const bm::RockingBody one = bm::RectangularBlock(B, H1 + H2, rho * B * (H1 + H2), 9.81);
    EXPECT_NEAR(stack.m_kg / one.m_kg, 1.0, 8 * kEps);
    EXPECT_NEAR(stack.h_m / one.h_m, 1.0, 8 * kEps);
    EXPECT_NEAR(stack.I_O_kgm2 / one.I_O_kgm2, 1.0, 8 * kEps);
    EXPECT_NEAR(stack.p_radps() / one.p_radps(), 1.0, 8 * kEps);
    EXPECT_NEAR(stack.alpha_rad() / one.alpha_rad(), 1.0, 8 * kEps);
    EXPECT_NEAR(bm::StackGroundImpact3aTo3b(p1, p2), bm::HousnerRestitution(one.alpha_rad()),
                8 * kEps);
  }
}

// The locked column of N blocks against independent forms of the same body. One block is
// Housner's (RectangularBlock: I_O = (4/3) m R^2 in one product, the column's I_G + m R^2 in
// two), two of different widths are the thesis's LockedStack (the same terms grouped another
// way: block 2's parallel axis about block 1's corner), both to a few roundings: 4 eps
// relative. N equal blocks are one block N times as tall: the column's I_O
// sums N terms of size up to m (2N h)^2 against one product, so (N + 3) roundings: 8 N eps
// relative bounds them. Their first-impact times (GSL quadrature to 1e-13 relative) then agree
// to the quadrature's tolerance, which 1e-12 relative holds with room.
TEST(ClosedFormsTest, LockedColumnIsHousnersBlockTheLockedStackAndOneTallBlock) {
  auto expect_same_body = [](const bm::RockingBody& a, const bm::RockingBody& b, double rel) {
    EXPECT_NEAR(a.m_kg / b.m_kg, 1.0, rel);
    EXPECT_NEAR(a.b_m / b.b_m, 1.0, rel);
    EXPECT_NEAR(a.h_m / b.h_m, 1.0, rel);
    EXPECT_NEAR(a.I_O_kgm2 / b.I_O_kgm2, 1.0, rel);
    EXPECT_EQ(a.g_mps2, b.g_mps2);
    const double theta0 = 0.5 * b.alpha_rad();
    EXPECT_NEAR(bm::FirstImpactTime_s(a, theta0) / bm::FirstImpactTime_s(b, theta0), 1.0, 1e-12);
  };
  for (const auto& [B, H] : {std::pair{1.0, 4.0}, std::pair{0.9, 0.85}, std::pair{0.2, 3.0}}) {
    SCOPED_TRACE(testing::Message() << "B " << B << ", H " << H);
    const BlockProps p = MakeBlockProps(B, H, 2500.0 * B * H);
    const bm::RockingBody housner = bm::RectangularBlock(B, H, 2500.0 * B * H, 9.81);
    expect_same_body(bm::LockedColumn(std::vector<BlockProps>{p}, 9.81), housner, 4 * kEps);
    // The same through the scene: a one-block scene is Housner's block.
    Scene sc;
    sc.blocks.push_back(BlockDef{B, H, 1.0, 2500.0 * B * H, 2500.0});
    expect_same_body(bm::LockedColumn(sc), housner, 4 * kEps);
    for (const int n : {2, 3, 6, 10}) {
      SCOPED_TRACE(testing::Message() << n << " equal blocks");
      const bm::RockingBody column = bm::LockedColumn(std::vector<BlockProps>(n, p), 9.81);
      const bm::RockingBody tall = bm::RectangularBlock(B, n * H, n * 2500.0 * B * H, 9.81);
      expect_same_body(column, tall, 8 * n * kEps);
    }
  }
  for (const auto& [B1, H1, B2, H2] :
       {std::tuple{1.25, 1.25, 1.0, 2.5}, std::tuple{1.0, 3.0, 0.5, 1.0}}) {
    const BlockProps p1 = MakeBlockProps(B1, H1, 2500.0 * B1 * H1),
                     p2 = MakeBlockProps(B2, H2, 2500.0 * B2 * H2);
    expect_same_body(bm::LockedColumn(std::vector<BlockProps>{p1, p2}, 9.81),
                     bm::LockedStack(p1, p2, 9.81), 4 * kEps);
  }
}

// As block 2's mass vanishes (m2 / m1 = mu), block 1 lands as if alone (3a -> 1b: theta1'+ /
// theta1'- -> Housner's e of block 1), and block 2 alone on a block 1 that cannot be moved
// (4a -> 1b) leaves it still (theta1'+ -> 0) and rocks on with its own e (theta2'+ / theta2'-
// -> the 4a -> 4b coefficient). The differences are O(mu): a tenth of mu, a tenth of each
// (ratio 10 within 1%: the O(mu^2) term, relative mu = 1e-4 at most, and rounding, 1e-16 / 1e-5
// of a difference of ~1e-5).
TEST(ClosedFormsTest, StackImpactsTendToOneBlockAsTheUpperMassVanishes) {
  for (const auto& [B1, H1, B2, H2] :
       {std::tuple{1.25, 1.25, 1.0, 2.5}, std::tuple{1.0, 3.0, 0.5, 1.0}}) {
    auto gaps = [&](double mu) {
      const BlockProps p1 = MakeBlockProps(B1, H1, 1000.0);
      const BlockProps p2 = MakeBlockProps(B2, H2, 1000.0 * mu);
      const bm::RateRatios g = bm::StackGroundImpact3aTo1b(p1, p2);
      const bm::RateRatios t = bm::TopBlockImpact4aTo1b(p1, p2);
      return std::vector<double>{g.theta1 - bm::HousnerRestitution(p1.theta_c), t.theta1,
                                 t.theta2 - bm::TopBlockImpact4aTo4b(p2)};
    };
    const std::vector<double> g4 = gaps(1e-4), g5 = gaps(1e-5);
    for (size_t i = 0; i < g4.size(); ++i) {
      EXPECT_GT(std::abs(g4[i]), 1e-7) << i;  // a real O(mu) difference, not zero
      EXPECT_NEAR(g4[i] / g5[i], 10.0, 0.1) << "gap " << i;
    }
  }
  // And 4a -> 4b is Housner's e of block 2 (eq. 5.36 for a rectangle).
  const BlockProps p2 = MakeBlockProps(1.0, 2.5, 6250.0);
  EXPECT_NEAR(bm::TopBlockImpact4aTo4b(p2), bm::HousnerRestitution(p2.theta_c), 8 * kEps);
}

Geometry RandomStack(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> slender(0.5, 10.0), width(0.3, 2.0);
  std::uniform_real_distribution<double> log_ratio(std::log(0.01), std::log(100.0));
  const double B1 = width(rng), H1 = B1 * slender(rng);
  const double B2 = B1 * std::uniform_real_distribution<double>(0.1, 1.0)(rng);
  const double H2 = B2 * slender(rng);
  const double m1 = 1000.0 * B1 * H1;
  return MakeGeometry(B1, H1, m1, B2, H2, m1 * std::exp(log_ratio(rng)));
}

// The reference's PostImpactState (generalized momenta of the post-impact mode, J^T M_b J u+ =
// J^T M_b V-, in the base frame) reproduces eqs. 5.29, 5.31, 5.34 and 5.36 (angular momenta
// about the new pivots, in closed form) on 2000 stacks of mass ratio 0.01 to 100 and
// slenderness 0.5 to 10. Bounds: the reference forms block 2's momentum from base-frame
// positions of size d = |G2 - O1| (block 1's corner to block 2's mass centre), while the
// result is set by block 2's own size r2: each rounding of a position is eps d, relative eps L
// with L = d / r2. One degree of freedom (5.31, 5.36): a ratio of such sums, bound 4 eps L
// (measured 1.2 eps L). Two (5.29, 5.34): Cramer's rule on the 2x2 mass matrix of mode 1b,
// whose rounding is amplified by its condition kappa = (|M00 M11| + |M01 M10|) / det, bound
// 32 eps kappa L (1 + |u1| + |u2|) (measured 9.2).
TEST(ClosedFormsTest, ReferenceImpactLawsAreTheThesisClosedForms) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const Geometry geo = RandomStack(rng);
    const BlockProps &p1 = geo.block1, &p2 = geo.block2;
    const double L = std::hypot(p1.b, 2.0 * p1.h + p2.h) / p2.r;
    const GeneralizedDynamics d = AssembleDynamics(geo, Mode::k1b, State{}, 0.0, 0.0);
    const double kappa = (std::abs(d.M[0][0] * d.M[1][1]) + std::abs(d.M[0][1] * d.M[1][0])) /
                         (d.M[0][0] * d.M[1][1] - d.M[0][1] * d.M[1][0]);
    const double w = -0.7;
    SCOPED_TRACE("trial " + std::to_string(trial));
    const State pre3{0.0, 0.0, w, w}, pre4{0.0, 0.0, 0.0, w};
    const bm::RateRatios r31 = bm::StackGroundImpact3aTo1b(p1, p2);
    const State s31 = PostImpactState(geo, Mode::k3a, pre3, Mode::k1b);
    const double tol31 = 32 * kEps * kappa * L * (1 + std::abs(r31.theta1) + std::abs(r31.theta2));
    EXPECT_NEAR(s31.omega1 / w, r31.theta1, tol31);
    EXPECT_NEAR(s31.omega2 / w, r31.theta2, tol31);
    const State s33 = PostImpactState(geo, Mode::k3a, pre3, Mode::k3b);
    EXPECT_NEAR(s33.omega1 / w, bm::StackGroundImpact3aTo3b(p1, p2), 4 * kEps * L);
    EXPECT_EQ(s33.omega1, s33.omega2);
    const bm::RateRatios r41 = bm::TopBlockImpact4aTo1b(p1, p2);
    const State s41 = PostImpactState(geo, Mode::k4a, pre4, Mode::k1b);
    const double tol41 = 32 * kEps * kappa * L * (1 + std::abs(r41.theta1) + std::abs(r41.theta2));
    EXPECT_NEAR(s41.omega1 / w, r41.theta1, tol41);
    EXPECT_NEAR(s41.omega2 / w, r41.theta2, tol41);
    const State s44 = PostImpactState(geo, Mode::k4a, pre4, Mode::k4b);
    EXPECT_NEAR(s44.omega2 / w, bm::TopBlockImpact4aTo4b(p2), 4 * kEps * L);
    EXPECT_EQ(s44.omega1, 0.0);
  }
}

// Whenever the reference (which asks both the rates and the impulses to be admissible, and
// tries more candidates than the thesis's two) ends a 3a ground impact in 1b or 3b, or a 4a
// interface impact in 1b or 4b, it is the outcome the thesis's rule picks; over the same 2000
// stacks both outcomes of each rule occur (so the test can fail either way).
TEST(ClosedFormsTest, ReferenceChoosesTheThesisOutcome) {
  std::mt19937_64 rng(3);
  int seen[2][2] = {{0, 0}, {0, 0}};  // [3a, 4a][thesis says 1b]
  for (int trial = 0; trial < 2000; ++trial) {
    const Geometry geo = RandomStack(rng);
    SCOPED_TRACE("trial " + std::to_string(trial));
    const bool g1b = bm::ThesisOutcomeAfter3aIs1b(geo.block1, geo.block2);
    const Mode ground =
        ResolveImpact(geo, Mode::k3a, {0.0, 0.0, -0.7, -0.7}, ImpactKind::kGround, 0.0).chosen.mode;
    if (ground == Mode::k1b || ground == Mode::k3b) {
      EXPECT_EQ(ground, g1b ? Mode::k1b : Mode::k3b);
      ++seen[0][g1b];
    }
    const bool t1b = bm::ThesisOutcomeAfter4aIs1b(geo.block1, geo.block2);
    const Mode top =
        ResolveImpact(geo, Mode::k4a, {0.0, 0.0, 0.0, -0.7}, ImpactKind::kInterface, 0.0)
            .chosen.mode;
    if (top == Mode::k1b || top == Mode::k4b) {
      EXPECT_EQ(top, t1b ? Mode::k1b : Mode::k4b);
      ++seen[1][t1b];
    }
  }
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(seen[k][0], 50) << k;
    EXPECT_GE(seen[k][1], 50) << k;
  }
}

// Outside a form's validity the library says so instead of returning a number.
TEST(ClosedFormsTest, ArgumentsOutsideTheFormsThrow) {
  const bm::RockingBody body = bm::RectangularBlock(1.0, 4.0, 10000.0, 9.81);
  const double a = body.alpha_rad();
  EXPECT_THROW(bm::FirstImpactTime_s(body, 0.0), std::domain_error);
  EXPECT_THROW(bm::FirstImpactTime_s(body, a), std::domain_error);
  EXPECT_THROW(bm::FreeRockingAmplitude_rad(body, 10.0), std::domain_error);
  EXPECT_THROW(bm::RectangularPulseOverturningAcceleration_mps2(body, 0.0), std::domain_error);
  EXPECT_THROW(bm::LockedStack(MakeBlockProps(1.0, 1.0, 1.0), MakeBlockProps(2.0, 1.0, 1.0), 9.81),
               std::domain_error);
  EXPECT_THROW(bm::LockedColumn(std::vector<BlockProps>{}, 9.81), std::domain_error);
  EXPECT_THROW(bm::LockedColumn(std::vector<BlockProps>{MakeBlockProps(1.0, 1.0, 1.0),
                                                        MakeBlockProps(0.5, 1.0, 1.0),
                                                        MakeBlockProps(0.6, 1.0, 1.0)},
                                9.81),
               std::domain_error);  // block 3 wider than block 2
  EXPECT_THROW(
      bm::FreeRockingAmplitudeAfterImpacts_rad(bm::RectangularBlock(1.0, 0.5, 1.0, 9.81), 0.1, 1),
      std::domain_error);  // squat: e < 0
}

}  // namespace
}  // namespace rockbench::reference
