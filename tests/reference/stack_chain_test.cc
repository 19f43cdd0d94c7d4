// The N-block pivot chain (reference/stack_chain.h) checked three ways:
// - against the thesis's explicit equations for two blocks (modes.cc, every mode) and for one
//   block (Housner), and their reactions and impact laws (kinematics.cc, impact.cc);
// - against an independent Lagrangian assembly written here, M(q) q'' = J^T (F - M_b a_vp), with
//   the Jacobian taken column by column from unit rates, for N up to 10 in every kind of
//   configuration;
// - against Newton-Euler on each block with the constraint forces: the loads the recursion
//   gives are those that Newton's and Euler's laws need for its accelerations, an open pivot
//   carries no moment, and the energy's rate is the power of the base's motion alone.
// Tolerances: the quantities are sums of O(N) products of O(1) terms, so their rounding is a
// few ulps times N times the largest term; 1e-11 relative (about 5e4 ulps) is that bound with
// a wide margin for the N <= 10 stacks here, and far below any modelling difference (a wrong
// sign or lever arm is O(1)).
#include "reference/chain/stack_chain.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "reference/thesis/geometry.h"
#include "reference/thesis/impact.h"
#include "reference/thesis/kinematics.h"
#include "reference/thesis/modes.h"

namespace rockbench::reference {
namespace {

constexpr double kRel = 1e-11;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// A stack of n blocks, each no wider than the one below, of random proportions and masses.
StackGeometry RandomStack(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> shrink(0.3, 1.0), aspect(0.2, 4.0), mass(10.0, 1e4);
  std::vector<BlockSize> sizes;
  double width = 1.0 + shrink(rng);
  for (int i = 0; i < n; ++i) {
    // Equal widths (drums) one time in four.
    if (i > 0 && rng() % 4 != 0) width *= shrink(rng);
    sizes.push_back({width, width * aspect(rng), mass(rng)});
  }
  return MakeStackGeometry(sizes, 9.81);
}

// A configuration and a state consistent with it: open interfaces tilt to their side
// (relative angle of that sign), closed ones carry the angle and rate of their support.
struct StackState {
  Configuration config;
  std::vector<double> theta, omega;
};
StackState RandomState(int n, std::mt19937_64& rng, double p_open = 0.6) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), rel(0.01, 0.3), rate(-2.0, 2.0);
  StackState s{Configuration(n), std::vector<double>(n), std::vector<double>(n)};
  double theta_below = 0.0, omega_below = 0.0;
  for (int k = 0; k < n; ++k) {
    if (unit(rng) < p_open) {
      const bool right = unit(rng) < 0.5;
      s.config.set(k, right ? Contact::kRight : Contact::kLeft);
      s.theta[k] = theta_below + (right ? 1.0 : -1.0) * rel(rng);
      s.omega[k] = omega_below + rate(rng);
    } else {
      s.theta[k] = theta_below;
      s.omega[k] = omega_below;
    }
    theta_below = s.theta[k];
    omega_below = s.omega[k];
  }
  return s;
}

void ExpectClose(double got, double want, double scale, const char* what, int k) {
  EXPECT_NEAR(got, want, kRel * scale) << what << " " << k;
}

// ---- The independent Lagrangian formulation ----

// Classical accelerations of every block (mass centre, counter-clockwise angular) for the
// absolute angular accelerations theta_dd, by the pivot chain: a point X of block k accelerates
// as its pivot plus alpha x (X - P) - w^2 (X - P).
void ClassicalAccelerations(const StackChain& chain, const std::vector<double>& theta_dd,
                            std::vector<Vec2>* aG, std::vector<double>* alpha) {
  const int n = chain.size();
  aG->assign(n, Vec2{});
  alpha->assign(n, 0.0);
  Vec2 A_pivot{};
  for (int k = 0; k < n; ++k) {
    const double w = chain.Body(k).w_radps, al = -theta_dd[k];
    const Vec2 P = chain.Pivot(k), G = chain.Body(k).G;
    (*aG)[k] = A_pivot + al * Perp(G - P) - (w * w) * (G - P);
    (*alpha)[k] = al;
    if (k + 1 < n) {
      const Vec2 P1 = chain.Pivot(k + 1);
      A_pivot = A_pivot + al * Perp(P1 - P) - (w * w) * (P1 - P);
    }
  }
}

// M(q) q'' = J^T (F - M_b a_vp), q the relative angles of the open interfaces; returns the
// absolute angular accelerations and a bound of the rounding either solution may carry in
// *rounding: a sum of n terms is good to about n ulps of the largest of them, so f is good to
// df = n eps sum |terms of f| and M to n eps |M| per entry; they move q'' by df / lambda_min(M)
// and cond(M) n eps |q''|. The recursion takes its moments about the origin (block 1's base
// centre), where the blocks' inertias are I_G + m |G|^2: its rounding is n eps of those over
// lambda_min(M), times |q''|.
std::vector<double> LagrangeAccelerations(const StackGeometry& geo, const StackState& s, double xg,
                                          double yg, double* rounding) {
  const int n = geo.size();
  StackChain chain(geo);
  std::vector<int> open;
  for (int k = 0; k < n; ++k) {
    if (s.config[k] != Contact::kFace) open.push_back(k);
  }
  const int dof = static_cast<int>(open.size());
  // Columns of the Jacobian: the blocks' velocities for a unit rate of one open interface.
  std::vector<std::vector<Vec2>> JG(dof, std::vector<Vec2>(n));
  std::vector<std::vector<double>> Jw(dof, std::vector<double>(n));
  for (int j = 0; j < dof; ++j) {
    std::vector<double> w(n, 0.0);
    for (int i = open[j]; i < n; ++i) w[i] = 1.0;  // every block from the interface up turns
    chain.Place(s.config, s.theta.data(), w.data());
    for (int i = 0; i < n; ++i) {
      JG[j][i] = chain.Body(i).vG;
      Jw[j][i] = chain.Body(i).w_radps;
    }
  }
  // The velocity-product accelerations: the classical ones at zero angular acceleration.
  chain.Place(s.config, s.theta.data(), s.omega.data());
  std::vector<Vec2> a_vp;
  std::vector<double> alpha0;
  ClassicalAccelerations(chain, std::vector<double>(n, 0.0), &a_vp, &alpha0);
  const Vec2 g_eff{-xg, -(geo.g + yg)};
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(dof, dof);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dof);
  double f_terms = 0.0;
  for (int i = 0; i < n; ++i) {
    const BlockProps& p = geo.blocks[i];
    for (int a = 0; a < dof; ++a) {
      f[a] += Dot(JG[a][i], p.m * (g_eff - a_vp[i]));
      f_terms += p.m * std::hypot(JG[a][i].x, JG[a][i].y) *
                 (std::hypot(g_eff.x, g_eff.y) + std::hypot(a_vp[i].x, a_vp[i].y));
      for (int b = 0; b < dof; ++b) {
        M(a, b) += p.m * Dot(JG[a][i], JG[b][i]) + p.I_G * Jw[a][i] * Jw[b][i];
      }
    }
  }
  using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  using VecL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  const VecL qddl = MatL(M.cast<long double>()).ldlt().solve(VecL(f.cast<long double>()));
  const Eigen::VectorXd qdd = qddl.cast<double>();
  *rounding = 0.0;
  if (dof > 0) {
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    const double eps_n = n * std::numeric_limits<double>::epsilon();
    double origin_inertia = 0.0;
    for (int i = 0; i < n; ++i) {
      const Vec2 G = chain.Body(i).G;
      origin_inertia += geo.blocks[i].I_G + geo.blocks[i].m * Dot(G, G);
    }
    *rounding = eps_n * (f_terms / ev.minCoeff() +
                         (ev.maxCoeff() + origin_inertia) / ev.minCoeff() * qdd.cwiseAbs().sum());
  }
  std::vector<double> theta_dd(n, 0.0);
  double below = 0.0;
  int j = 0;
  for (int k = 0; k < n; ++k) {
    if (j < dof && open[j] == k) below += qdd[j++];
    theta_dd[k] = below;
  }
  return theta_dd;
}

// ---- One and two blocks: the thesis's equations ----

constexpr Mode kModes[] = {Mode::kRest, Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b,
                           Mode::k3a,   Mode::k3b, Mode::k4a, Mode::k4b};

// A state of the thesis's two blocks in `mode`, on the mode's constraints.
State ThesisState(Mode mode, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0.01, 0.5), rate(-3.0, 3.0);
  const Contacts c = ContactsOf(mode);
  const double side1 = c.ground == Contact::kLeft ? -1.0 : 1.0;
  const double side2 = c.interface == Contact::kLeft ? -1.0 : 1.0;
  State s;
  s.theta1 = c.ground == Contact::kFace ? 0.0 : side1 * angle(rng);
  s.omega1 = c.ground == Contact::kFace ? 0.0 : rate(rng);
  s.theta2 = c.interface == Contact::kFace ? s.theta1 : s.theta1 + side2 * angle(rng);
  s.omega2 = c.interface == Contact::kFace ? s.omega1 : rate(rng);
  return s;
}

TEST(StackChainTest, TwoBlocksFollowTheThesisEquationsInEveryMode) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> acc(-8.0, 8.0);
  // The thesis's stack and a squat one on a slender one, block 2 narrower and as wide.
  const double shapes[][6] = {{1.25, 1.25, 3000, 1.0, 2.5, 4000},
                              {0.6, 2.4, 800, 0.6, 0.5, 150},
                              {2.0, 1.0, 5e3, 0.3, 1.5, 40}};
  for (const auto& sh : shapes) {
    const Geometry geo = MakeGeometry(sh[0], sh[1], sh[2], sh[3], sh[4], sh[5], 9.81);
    StackChain chain(MakeStackGeometry({{sh[0], sh[1], sh[2]}, {sh[3], sh[4], sh[5]}}, 9.81));
    for (const Mode mode : kModes) {
      for (int trial = 0; trial < 20; ++trial) {
        const State s = ThesisState(mode, rng);
        const double xg = acc(rng), yg = trial % 2 ? acc(rng) : 0.0;
        const auto want = ModeAccelerations(geo, mode, s, xg, yg, Equations::kNonlinear);
        const double theta[2] = {s.theta1, s.theta2}, omega[2] = {s.omega1, s.omega2};
        double got[2];
        InterfaceLoad loads[2];
        chain.Place(ConfigurationOf(mode, 2), theta, omega);
        chain.Accelerations(xg, yg, got, loads);
        const double scale = 1.0 + std::abs(want[0]) + std::abs(want[1]);
        ExpectClose(got[0], want[0], scale, ModeName(mode).data(), trial);
        ExpectClose(got[1], want[1], scale, ModeName(mode).data(), trial);
        // The reactions, from kinematics.cc's Newton-Euler on the thesis's accelerations.
        const Reactions r = ComputeReactions(geo, mode, s, want, xg, yg);
        const double W = geo.M * (geo.g + std::abs(yg) + std::abs(xg)) * scale;
        ExpectClose(loads[0].normal_n, r.N_ground, W, "N ground", trial);
        ExpectClose(loads[0].tangential_n, r.T_ground, W, "T ground", trial);
        ExpectClose(loads[1].normal_n, r.N_interface, W, "N interface", trial);
        ExpectClose(loads[1].tangential_n, r.T_interface, W, "T interface", trial);
        if (ContactsOf(mode).ground == Contact::kFace) {
          ExpectClose(loads[0].left_n, r.ground_left, W, "ground left", trial);
          ExpectClose(loads[0].right_n, r.ground_right, W, "ground right", trial);
        }
        if (ContactsOf(mode).interface == Contact::kFace) {
          ExpectClose(loads[1].left_n, r.interface_left, W, "interface left", trial);
          ExpectClose(loads[1].right_n, r.interface_right, W, "interface right", trial);
        }
      }
    }
  }
}

TEST(StackChainTest, OneBlockIsHousnersBlock) {
  // I_O theta'' = m g R sin(theta - S theta_c) - m R xg'' cos(theta - S theta_c) (+ yg'' in g),
  // about the corner on the side S of the tilt.
  const double B = 0.8, H = 2.4, m = 500.0, g = 9.81;
  const BlockProps p = MakeBlockProps(B, H, m);
  StackChain chain(MakeStackGeometry({{B, H, m}}, g));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> angle(-0.4, 0.4), rate(-2, 2), acc(-5, 5);
  for (int trial = 0; trial < 50; ++trial) {
    const double theta = angle(rng), omega = rate(rng), xg = acc(rng), yg = acc(rng);
    const double S = theta >= 0.0 ? 1.0 : -1.0;
    Configuration c(1);
    c.set(0, S > 0 ? Contact::kRight : Contact::kLeft);
    double got;
    chain.Place(c, &theta, &omega);
    chain.Accelerations(xg, yg, &got);
    const double want =
        p.m * p.r *
        ((g + yg) * std::sin(theta - S * p.theta_c) - xg * std::cos(theta - S * p.theta_c)) / p.I_O;
    ExpectClose(got, want, 1.0 + std::abs(want), "housner", trial);
  }
}

// ---- Any N: the Lagrangian assembly and Newton-Euler ----

TEST(StackChainTest, AccelerationsEqualTheLagrangianAssemblyUpToTenBlocks) {
  std::mt19937_64 rng(7);
  double worst_rel = 0.0;
  std::uniform_real_distribution<double> acc(-6.0, 6.0);
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 40; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      const StackState s = RandomState(n, rng, trial % 4 == 0 ? 1.0 : 0.6);
      const double xg = acc(rng), yg = trial % 3 ? acc(rng) : 0.0;
      StackChain chain(geo);
      std::vector<double> got(n);
      chain.Place(s.config, s.theta.data(), s.omega.data());
      chain.Accelerations(xg, yg, got.data());
      double rounding = 0.0;
      const std::vector<double> want = LagrangeAccelerations(geo, s, xg, yg, &rounding);
      // The absolute accelerations sum up to n relative ones: n times the bound, and a factor
      // 8 for the recursion's own rounding, which has the same sources.
      const double tol = 8.0 * n * rounding + 4 * kEps;
      for (int k = 0; k < n; ++k) {
        EXPECT_NEAR(got[k], want[k], tol) << k << " of " << n;
        worst_rel = std::max(worst_rel, std::abs(got[k] - want[k]) / tol);
      }
      // A closed interface's block turns with its support.
      for (int k = 0; k < n; ++k) {
        if (s.config[k] == Contact::kFace) {
          EXPECT_EQ(got[k], k == 0 ? 0.0 : got[k - 1]) << k;
        }
      }
    }
  }
  std::printf("largest difference: %.3g of its bound\n", worst_rel);
}

TEST(StackChainTest, LoadsAreNewtonEulersAndOpenPivotsCarryNoMoment) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> acc(-6.0, 6.0);
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 30; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      const StackState s = RandomState(n, rng);
      const double xg = acc(rng), yg = acc(rng);
      StackChain chain(geo);
      std::vector<double> theta_dd(n);
      std::vector<InterfaceLoad> loads(n), ne(n);
      chain.Place(s.config, s.theta.data(), s.omega.data());
      chain.Accelerations(xg, yg, theta_dd.data(), loads.data());
      std::vector<Vec2> aG;
      std::vector<double> alpha;
      ClassicalAccelerations(chain, theta_dd, &aG, &alpha);
      const Vec2 g_eff{-xg, -(geo.g + yg)};
      chain.LoadsFor(aG.data(), alpha.data(), g_eff, ne.data());
      double weight = 0.0;
      for (const BlockProps& p : geo.blocks) weight += p.m * (geo.g + 12.0);
      for (int k = 0; k < n; ++k) {
        ExpectClose(loads[k].normal_n, ne[k].normal_n, weight, "N", k);
        ExpectClose(loads[k].tangential_n, ne[k].tangential_n, weight, "T", k);
        ExpectClose(loads[k].left_n, ne[k].left_n, weight, "left", k);
        ExpectClose(loads[k].right_n, ne[k].right_n, weight, "right", k);
      }
      // Euler about each open pivot: the blocks above it need no moment there.
      for (int k = 0; k < n; ++k) {
        if (s.config[k] == Contact::kFace) continue;
        double moment = 0.0;
        const Vec2 P = chain.Pivot(k);
        for (int i = k; i < n; ++i) {
          const BlockProps& p = geo.blocks[i];
          moment += p.I_G * alpha[i] + Cross(chain.Body(i).G - P, p.m * (aG[i] - g_eff));
        }
        double arm = 0.0;
        for (int i = k; i < n; ++i) arm += 2.0 * geo.blocks[i].h + geo.blocks[i].b;
        EXPECT_NEAR(moment, 0.0, kRel * weight * arm) << "pivot " << k << " of " << n;
      }
    }
  }
}

TEST(StackChainTest, EnergyChangesOnlyByTheBasesPower) {
  // dE/dt = sum m vG . aG + I_G w alpha + m g vG.y; with the base still it is zero (the contact
  // forces do no work: pivots do not move), with a base acceleration it is the power of the
  // inertial force, sum m vG . (-xg'', -yg'').
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> acc(-6.0, 6.0);
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      const StackState s = RandomState(n, rng);
      const double xg = trial % 2 ? acc(rng) : 0.0, yg = trial % 2 ? acc(rng) : 0.0;
      StackChain chain(geo);
      std::vector<double> theta_dd(n);
      chain.Place(s.config, s.theta.data(), s.omega.data());
      chain.Accelerations(xg, yg, theta_dd.data());
      std::vector<Vec2> aG;
      std::vector<double> alpha;
      ClassicalAccelerations(chain, theta_dd, &aG, &alpha);
      double power = 0.0, base_power = 0.0, scale = 0.0;
      for (int i = 0; i < n; ++i) {
        const BlockProps& p = geo.blocks[i];
        const BodyMotion b = chain.Body(i);
        power += p.m * Dot(b.vG, aG[i]) + p.I_G * b.w_radps * alpha[i] + p.m * geo.g * b.vG.y;
        base_power += p.m * Dot(b.vG, Vec2{-xg, -yg});
        scale += p.m * (std::hypot(b.vG.x, b.vG.y) * (geo.g + 12.0 + std::hypot(aG[i].x, aG[i].y)));
      }
      EXPECT_NEAR(power, base_power, kRel * scale) << n << " blocks, trial " << trial;
    }
  }
}

// ---- Impacts ----

TEST(StackChainTest, OneBlockImpactIsHousnersCoefficient) {
  // Rocking onto the other corner: omega+ = omega- (1 - 1.5 sin^2 theta_c).
  for (const double aspect : {0.25, 0.5, 1.0, 3.0}) {
    const double B = 0.5, H = B * aspect;
    const BlockProps p = MakeBlockProps(B, H, 100.0);
    StackChain chain(MakeStackGeometry({{B, H, 100.0}}));
    Configuration before(1), after(1);
    before.set(0, Contact::kRight);
    after.set(0, Contact::kLeft);
    const double theta = 0.0, omega_minus = -1.3;
    double omega_plus;
    chain.Place(before, &theta, &omega_minus);
    chain.ImpactRates(after, &omega_plus);
    const double s = std::sin(p.theta_c);
    EXPECT_NEAR(omega_plus, omega_minus * (1.0 - 1.5 * s * s), 1e-14) << aspect;
  }
}

TEST(StackChainTest, TwoBlockImpactsAreTheThesisLaws) {
  // Every pre-impact mode, every post-impact mode the impact module offers, against its
  // conservation of generalized momenta (impact.cc PostImpactState).
  std::mt19937_64 rng(3);
  const Geometry geo = MakeGeometry(1.25, 1.25, 3000, 1.0, 2.5, 4000, 9.81);
  StackChain chain(MakeStackGeometry({{1.25, 1.25, 3000}, {1.0, 2.5, 4000}}));
  for (const Mode before : kModes) {
    if (before == Mode::kRest) continue;
    const Contacts c = ContactsOf(before);
    for (const ImpactKind kind : {ImpactKind::kGround, ImpactKind::kInterface}) {
      if (kind == ImpactKind::kGround && c.ground == Contact::kFace) continue;
      if (kind == ImpactKind::kInterface && c.interface == Contact::kFace) continue;
      State pre = ThesisState(before, rng);
      // The impacting gap is closed.
      if (kind == ImpactKind::kGround) {
        const double rel = pre.theta2 - pre.theta1;
        pre.theta1 = 0.0;
        pre.theta2 = c.interface == Contact::kFace ? 0.0 : rel;
      } else {
        pre.theta2 = pre.theta1;
      }
      for (const Mode after : ImpactCandidates(before, kind, true)) {
        const State want = PostImpactState(geo, before, pre, after);
        const double theta[2] = {pre.theta1, pre.theta2}, omega[2] = {pre.omega1, pre.omega2};
        double got[2];
        chain.Place(ConfigurationOf(before, 2), theta, omega);
        chain.ImpactRates(ConfigurationOf(after, 2), got);
        const double scale = std::abs(pre.omega1) + std::abs(pre.omega2);
        EXPECT_NEAR(got[0], want.omega1, kRel * scale)
            << ModeName(before) << " -> " << ModeName(after);
        EXPECT_NEAR(got[1], want.omega2, kRel * scale)
            << ModeName(before) << " -> " << ModeName(after);
      }
    }
  }
}

TEST(StackChainTest, ImpactsNeverAddEnergyAndTheirImpulsesAreNewtonEulers) {
  // A plastic impact projects the velocities onto the post-impact configuration in the kinetic
  // energy's metric: the energy after is at most the energy before, for any configuration
  // after. The impulses are the jumps of the momenta of the blocks above each interface.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 30; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      StackState s = RandomState(n, rng, 0.8);
      // Close one open interface's gap: the impacting one.
      int k_imp = -1;
      for (int k = 0; k < n && k_imp < 0; ++k) {
        if (s.config[k] != Contact::kFace) k_imp = k;
      }
      if (k_imp < 0) continue;
      const double shift = (k_imp == 0 ? 0.0 : s.theta[k_imp - 1]) - s.theta[k_imp];
      // The blocks from it up turn by the same angle: those above keep their relative angles.
      for (int i = k_imp; i < n; ++i) s.theta[i] += shift;
      // After: the impacting interface on its other corner or closed; the closed ones above
      // may open (as an impact on a locked stack can).
      Configuration after = s.config;
      after.set(k_imp, unit(rng) < 0.5 ? Contact::kFace
                                       : (s.config[k_imp] == Contact::kRight ? Contact::kLeft
                                                                             : Contact::kRight));
      StackChain chain(geo);
      chain.Place(s.config, s.theta.data(), s.omega.data());
      const double e_before = chain.Energy();
      std::vector<BodyMotion> pre(n);
      for (int i = 0; i < n; ++i) pre[i] = chain.Body(i);
      std::vector<double> omega_plus(n);
      std::vector<InterfaceLoad> impulses(n), ne(n);
      chain.ImpactRates(after, omega_plus.data(), impulses.data());
      const double e_after = chain.Energy();
      EXPECT_LE(e_after, e_before + 1e-12 * std::abs(e_before)) << n << " blocks, " << trial;
      // Newton-Euler with the velocity jumps.
      std::vector<Vec2> dv(n);
      std::vector<double> dw(n);
      double p_scale = 0.0;
      for (int i = 0; i < n; ++i) {
        dv[i] = chain.Body(i).vG - pre[i].vG;
        dw[i] = chain.Body(i).w_radps - pre[i].w_radps;
        p_scale += geo.blocks[i].m * (std::hypot(pre[i].vG.x, pre[i].vG.y) + 1.0);
      }
      chain.LoadsFor(dv.data(), dw.data(), Vec2{}, ne.data());
      for (int k = 0; k < n; ++k) {
        ExpectClose(impulses[k].normal_n, ne[k].normal_n, p_scale, "impulse N", k);
        ExpectClose(impulses[k].tangential_n, ne[k].tangential_n, p_scale, "impulse T", k);
        ExpectClose(impulses[k].left_n, ne[k].left_n, p_scale, "impulse left", k);
        ExpectClose(impulses[k].right_n, ne[k].right_n, p_scale, "impulse right", k);
      }
    }
  }
}

}  // namespace
}  // namespace rockbench::reference
