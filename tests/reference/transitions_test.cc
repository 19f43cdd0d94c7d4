// Mode changes without impact: the generic face-corner-force rule (transitions.cc) against the
// thesis's printed criteria (eqs. 4.1-4.4, 4.47, 4.51), and its consistency with the
// equations of the mode it opens into.
#include "reference/thesis/transitions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "reference/thesis/modes.h"

namespace rockbench::reference {
namespace {

Geometry ThesisGeometry() {
  return MakeGeometry(1.25, 1.25, 3906.25, 1.0, 2.5, 6250.0);
}

// From rest, the mode selected by the corner-force rule is the one the thesis's initiation
// criteria (4.1 to 4.4, checked in that order) give, over random base accelerations and
// geometries. Points within 1e-9 g of a criterion's boundary are skipped (either answer is
// right there).
TEST(TransitionsTest, InitiationFromRestMatchesThesis41To44) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> acc(-15.0, 15.0), slender(0.5, 6.0), w(0.3, 2.0);
  int moved = 0, differs = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double B1 = w(rng), H1 = B1 * slender(rng);
    const double B2 = B1 * std::uniform_real_distribution<double>(0.2, 1.0)(rng);
    const double H2 = B2 * slender(rng);
    const Geometry geo = MakeGeometry(B1, H1, 2000 * B1 * H1, B2, H2, 2500 * B2 * H2);
    const double xg = acc(rng), yg = 0.5 * acc(rng);
    if (yg < -0.9 * geo.g) continue;
    const double g = geo.g, b1 = geo.block1.b, h = geo.h_stack, b2 = geo.block2.b,
                 h2 = geo.block2.h;
    const double margins[4] = {-h * xg - b1 * yg - b1 * g, h * xg - b1 * yg - b1 * g,
                               -h2 * xg - b2 * yg - b2 * g, h2 * xg - b2 * yg - b2 * g};
    bool near = false;
    for (double m : margins) near = near || std::abs(m) < 1e-9 * g * (h + b1);
    if (near) continue;
    const Mode thesis = ThesisInitiation(geo, xg, yg);
    const ModeSelection sel = SelectMode(geo, State{}, xg, yg, Equations::kNonlinear);
    ASSERT_TRUE(sel.consistent);
    if (thesis == Mode::kRest || sel.mode == Mode::kRest) {
      EXPECT_EQ(sel.mode, thesis) << "xg " << xg << " yg " << yg;
      continue;
    }
    ++moved;
    // The contact problem has exactly one consistent mode.
    int consistent = 0;
    for (Mode m :
         {Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b, Mode::k3a, Mode::k3b, Mode::k4a, Mode::k4b}) {
      consistent += ModeConsistent(geo, m, State{}, xg, yg, Equations::kNonlinear);
    }
    EXPECT_EQ(consistent, 1);
    if (sel.mode == thesis) continue;
    // The thesis checks 4.1 (mode 3) before 4.3 (mode 4). When both hold, the stack cannot
    // rock as one (block 2 would lift off block 1 at once): the consistent mode is then mode 4
    // (4.3/4.4 hold) or both contacts open (mode 1 or 2).
    ++differs;
    const bool stack_tips = thesis == Mode::k3a || thesis == Mode::k3b;
    EXPECT_TRUE(stack_tips) << ModeName(sel.mode) << " vs thesis " << ModeName(thesis);
    const bool right = thesis == Mode::k3a;
    const Mode m = sel.mode;
    const bool mode4_holds = right ? margins[2] > 0 : margins[3] > 0;
    EXPECT_TRUE((m == (right ? Mode::k4a : Mode::k4b) && mode4_holds) ||
                (right && (m == Mode::k1a || m == Mode::k2a)) ||
                (!right && (m == Mode::k1b || m == Mode::k2b)))
        << ModeName(m) << " vs thesis " << ModeName(thesis);
  }
  std::printf("initiation: %d starts, %d differ from the thesis's first criterion\n", moved,
              differs);
  EXPECT_GT(moved, 5000);
}

// Eq. 4.47 (mode 3a -> 1a) as printed equals the rule: block 2's left corner force turns
// tensile exactly when 4.47 holds.
TEST(TransitionsTest, Criterion447AsPrinted) {
  const Geometry geo = ThesisGeometry();
  const BlockProps& p2 = geo.block2;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int n = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double th = 0.3 * std::abs(u(rng)) + 1e-3;
    const State s{th, th, 2 * u(rng), 0.0};
    State s3 = s;
    s3.omega2 = s3.omega1;
    const double xg = 20 * u(rng), yg = 5 * u(rng);
    const double tdd = ModeAccelerations(geo, Mode::k3a, s3, xg, yg)[0];
    const double a = p2.theta_c - th, w2 = s3.omega1 * s3.omega1;
    const double lhs = -std::cos(a) * xg - std::sin(a) * yg;
    const double rhs = geo.g * std::sin(a) + geo.d * std::cos(p2.theta_c + geo.omega_d) * w2 +
                       (geo.d * std::sin(p2.theta_c + geo.omega_d) + p2.I_G / (p2.m * p2.r)) * tdd;
    const ContactMargins cm = EvaluateContacts(geo, Mode::k3a, s3, xg, yg, Equations::kNonlinear);
    if (cm.reactions.N_interface <= 0.0 || std::abs(lhs - rhs) < 1e-9 * geo.g) continue;
    EXPECT_EQ(lhs > rhs, cm.reactions.interface_left < 0.0) << trial;
    ++n;
  }
  EXPECT_GT(n, 15000);
}

// Eq. 4.51 (mode 4a -> 1a) as printed lacks block 2's weight on block 1 (m2 xi g, which its
// yg'' term carries): with that term the criterion equals the rule; without it, it does not.
TEST(TransitionsTest, Criterion451NeedsTheWeightOfBlock2) {
  const Geometry geo = ThesisGeometry();
  const BlockProps& p1 = geo.block1;
  const BlockProps& p2 = geo.block2;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int printed_disagrees = 0, n = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const State s{0.0, 0.3 * std::abs(u(rng)) + 1e-3, 0.0, 2 * u(rng)};
    const double xg = 20 * u(rng), yg = 5 * u(rng);
    const double t2dd = ModeAccelerations(geo, Mode::k4a, s, xg, yg)[1];
    const double a = p2.theta_c - s.theta2;
    const double lhs = -(p1.m + 2 * p2.m) * p1.h * xg - (p1.m * p1.b + p2.m * geo.xi) * yg;
    const double rhs_printed =
        p2.m * p2.r * (geo.xi * std::sin(a) + 2 * p1.h * std::cos(a)) * t2dd +
        p2.m * p2.r * (2 * p1.h * std::sin(a) - geo.xi * std::cos(a)) * s.omega2 * s.omega2 +
        p1.m * p1.b * geo.g;
    const double rhs = rhs_printed + p2.m * geo.xi * geo.g;
    const ContactMargins cm = EvaluateContacts(geo, Mode::k4a, s, xg, yg, Equations::kNonlinear);
    if (std::abs(lhs - rhs) < 1e-9 * geo.M * geo.g) continue;
    EXPECT_EQ(lhs > rhs, cm.reactions.ground_left < 0.0) << trial;
    printed_disagrees += (lhs > rhs_printed) != (cm.reactions.ground_left < 0.0);
    ++n;
  }
  EXPECT_GT(n, 15000);
  EXPECT_GT(printed_disagrees, 100);
}

// At the instant a face's corner force reaches zero, the mode it opens into has zero opening
// acceleration: the two descriptions agree at the switch (no jump in accelerations). Found by
// bisection on theta along a free-rocking state of the thesis's example, where mode 3a opens
// into 1a without impact.
TEST(TransitionsTest, FaceOpensWhereTheOpeningAccelerationVanishes) {
  const Geometry geo = ThesisGeometry();
  const double w = -0.27;
  auto corner = [&](double th) {
    const State s{th, th, w, w};
    return EvaluateContacts(geo, Mode::k3a, s, 0, 0, Equations::kNonlinear)
        .reactions.interface_left;
  };
  double lo = 0.09, hi = 0.12;  // corner(lo) < 0 < corner(hi)
  ASSERT_LT(corner(lo), 0.0);
  ASSERT_GT(corner(hi), 0.0);
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (corner(mid) < 0 ? lo : hi) = mid;
  }
  const State s{lo, lo, w, w};
  const auto a1 = ModeAccelerations(geo, Mode::k1a, s, 0, 0);
  const auto a3 = ModeAccelerations(geo, Mode::k3a, s, 0, 0);
  // |theta''| ~ 1 rad/s^2; the root is located to ~1e-16 rad in theta.
  EXPECT_NEAR(a1[1] - a1[0], 0.0, 1e-12);
  EXPECT_NEAR(a1[0], a3[0], 1e-12);
}

// Vertical ground acceleration below -g pulls the blocks off the ground: no mode is consistent
// (the model's no-uplift assumption fails).
TEST(TransitionsTest, FreeFallIsInconsistent) {
  const Geometry geo = ThesisGeometry();
  EXPECT_TRUE(SelectMode(geo, State{}, 0.0, -0.5 * geo.g, Equations::kNonlinear).consistent);
  EXPECT_FALSE(SelectMode(geo, State{}, 0.0, -1.2 * geo.g, Equations::kNonlinear).consistent);
}

// A body toppling from rest about a fixed corner (one block, or the stack in mode 3) has, by
// energy and Newton's law for the mass centre, the ground reaction
//   N = M g [1 - (1 + 2c - 3c^2) / kappa],  c = cos(theta - theta_c), kappa = I_O / (M R^2),
// whose minimum over c (at c = 1/3) is M g (1 - 4 / (3 kappa)). One rectangle has kappa = 4/3
// exactly: N = (M g / 4)(1 - 3c)^2 touches zero but stays compressive. The thesis's stack has
// kappa = 1.367 > 4/3: compressive throughout. A stack whose mass sits in a small block on a
// wide light base has kappa < 4/3: its pivot would have to pull, first at
// c* = (1 + sqrt(4 - 3 kappa)) / 3, so it would jump off its corner before reaching pi/2. The
// model's reactions (generic Lagrangian accelerations + Newton-Euler) match the closed form to
// 1e-12 M g (rounding of a dozen terms of size M g).
TEST(TransitionsTest, TopplingFromRestGroundReactionClosedForm) {
  const Geometry single = MakeGeometry(1.0, 4.0, 4000.0, 0.0, 0.0, 0.0);
  const Geometry thesis = ThesisGeometry();
  const Geometry compact_top = MakeGeometry(2.0, 0.1, 10.0, 0.2, 0.2, 1000.0);
  const auto kappa_of = [](const Geometry& geo) { return geo.I_O / (geo.M * geo.R * geo.R); };
  const auto state_at = [](const Geometry& geo, double phi) {
    const double omega = std::sqrt(2.0 * geo.M * geo.g * geo.R * (1.0 - std::cos(phi)) / geo.I_O);
    return State{geo.theta_c + phi, geo.theta_c + phi, omega, omega};
  };
  const auto ground_n = [](const Geometry& geo, const State& s) {
    const auto acc = GenericAccelerations(geo, Mode::k3a, s, 0.0, 0.0);
    return ComputeReactions(geo, Mode::k3a, s, acc, 0.0, 0.0).N_ground;
  };
  for (const Geometry* geo : {&single, &thesis, &compact_top}) {
    const double kappa = kappa_of(*geo);
    const double weight = geo->M * geo->g;
    for (double phi = 0.0; phi < 1.5; phi += 0.05) {
      const double c = std::cos(phi);
      EXPECT_NEAR(ground_n(*geo, state_at(*geo, phi)),
                  weight * (1.0 - (1.0 + 2.0 * c - 3.0 * c * c) / kappa), 1e-12 * weight)
          << "kappa " << kappa << ", phi " << phi;
    }
  }
  EXPECT_NEAR(kappa_of(single), 4.0 / 3.0, 1e-15);
  EXPECT_GT(kappa_of(thesis), 4.0 / 3.0);
  // Where the compact-top stack's pivot force first vanishes: compressive before, tensile after.
  const double kappa = kappa_of(compact_top);
  ASSERT_LT(kappa, 4.0 / 3.0);
  const double phi_star = std::acos((1.0 + std::sqrt(4.0 - 3.0 * kappa)) / 3.0);
  EXPECT_GT(ground_n(compact_top, state_at(compact_top, phi_star - 1e-3)), 0.0);
  EXPECT_LT(ground_n(compact_top, state_at(compact_top, phi_star + 1e-3)), 0.0);
}

}  // namespace
}  // namespace rockbench::reference
