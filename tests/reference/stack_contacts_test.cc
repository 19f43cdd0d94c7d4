// The N-block contact problem (reference/stack_contacts.h): for two blocks the same choices
// as the thesis's model (transitions.cc SelectMode, impact.cc ResolveImpact); for any N the
// static tipping thresholds in closed form, the uniqueness of the consistent configuration and
// of the admissible impact outcome, Housner's impact for one block, and no energy gained at any
// impact.
#include "reference/chain/stack_contacts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "reference/thesis/geometry.h"
#include "reference/thesis/impact.h"
#include "reference/thesis/transitions.h"

namespace rockbench::reference {
namespace {

StackGeometry RandomStack(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> shrink(0.3, 1.0), aspect(0.3, 5.0), density(1e3, 3e3);
  std::vector<BlockSize> sizes;
  double width = 0.5 + shrink(rng);
  for (int i = 0; i < n; ++i) {
    if (i > 0 && rng() % 3 != 0) width *= shrink(rng);
    const double height = width * aspect(rng);
    sizes.push_back({width, height, density(rng) * width * height});
  }
  return MakeStackGeometry(sizes, 9.81);
}

// A random state in which each interface is closed (exactly) with probability p_closed, else
// tilted to a random side with a random rate.
void RandomState(int n, double p_closed, std::mt19937_64& rng, std::vector<double>* theta,
                 std::vector<double>* omega) {
  std::uniform_real_distribution<double> unit(0, 1), rel(0.01, 0.3), rate(-2, 2);
  theta->assign(n, 0.0);
  omega->assign(n, 0.0);
  double tb = 0.0, wb = 0.0;
  for (int k = 0; k < n; ++k) {
    if (unit(rng) < p_closed) {
      (*theta)[k] = tb;
      (*omega)[k] = wb;
    } else {
      (*theta)[k] = tb + (unit(rng) < 0.5 ? -1 : 1) * rel(rng);
      (*omega)[k] = wb + rate(rng);
    }
    tb = (*theta)[k];
    wb = (*omega)[k];
  }
}

TEST(StackContactsTest, TwoBlocksSelectTheThesisModelsMode) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> acc(-15.0, 15.0), unit(0, 1);
  int moved = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const StackGeometry sg = RandomStack(2, rng);
    const BlockProps &p1 = sg.blocks[0], &p2 = sg.blocks[1];
    const Geometry geo = MakeGeometry(2 * p1.b, 2 * p1.h, p1.m, 2 * p2.b, 2 * p2.h, p2.m, sg.g);
    StackContacts contacts(sg);
    std::vector<double> theta, omega;
    RandomState(2, trial % 2 ? 0.5 : 1.0, rng, &theta, &omega);
    const double xg = acc(rng), yg = 0.4 * acc(rng);
    const State s{theta[0], theta[1], omega[0], omega[1]};
    const ModeSelection want = SelectMode(geo, s, xg, yg, Equations::kNonlinear);
    const StackSelection got = contacts.Select(theta.data(), omega.data(), xg, yg);
    ASSERT_EQ(got.consistent, want.consistent) << trial;
    if (!want.consistent) continue;
    EXPECT_EQ(ConfigurationName(got.config), ModeName(want.mode)) << trial;
    moved += want.mode != Mode::kRest;
  }
  EXPECT_GT(moved, 1000);
}

TEST(StackContactsTest, FromRestTheSubStackWithTheLowestThresholdTipsFirst) {
  // At rest the stack is static: the blocks from k up tip on block k - 1 (or the ground) when
  // the base's acceleration a to the left exceeds b_k g / H_k, H_k the height of their mass
  // centre above block k's base (thesis 4.1 for one interface). Just below the smallest
  // threshold nothing moves; just above it exactly that interface opens, to the right.
  std::mt19937_64 rng(9);
  int checked = 0;
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      StackContacts contacts(geo);
      std::vector<double> threshold(n);
      double m_above = 0.0, moment = 0.0;
      for (int k = n - 1; k >= 0; --k) {
        const BlockProps& p = geo.blocks[k];
        moment += m_above * 2.0 * p.h + p.m * p.h;
        m_above += p.m;
        threshold[k] = p.b * geo.g / (moment / m_above);
      }
      const int first = static_cast<int>(std::min_element(threshold.begin(), threshold.end()) -
                                         threshold.begin());
      std::vector<double> second = threshold;
      second[first] = INFINITY;
      const double gap = *std::min_element(second.begin(), second.end()) / threshold[first];
      if (gap < 1.01) continue;  // two thresholds within 1%: the margin below would mix them
      const std::vector<double> zero(n, 0.0);
      const StackSelection below =
          contacts.Select(zero.data(), zero.data(), -threshold[first] * (1 - 1e-6), 0.0);
      ASSERT_TRUE(below.consistent);
      EXPECT_TRUE(below.config.at_rest()) << ConfigurationName(below.config);
      const StackSelection above =
          contacts.Select(zero.data(), zero.data(), -threshold[first] * (1 + 1e-6), 0.0);
      ASSERT_TRUE(above.consistent);
      Configuration want(n);
      want.set(first, Contact::kRight);
      EXPECT_EQ(ConfigurationName(above.config), ConfigurationName(want))
          << n << " blocks, trial " << trial;
      // And mirrored.
      const StackSelection left =
          contacts.Select(zero.data(), zero.data(), threshold[first] * (1 + 1e-6), 0.0);
      want.set(first, Contact::kLeft);
      EXPECT_EQ(ConfigurationName(left.config), ConfigurationName(want));
      ++checked;
    }
  }
  EXPECT_GT(checked, 150);
}

TEST(StackContactsTest, AtMostOneConfigurationIsConsistent) {
  // Every configuration of the closed interfaces, for up to 5 blocks: none or one consistent,
  // and Select finds it.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> acc(-20.0, 20.0);
  int found = 0;
  for (int n = 1; n <= 5; ++n) {
    for (int trial = 0; trial < 60; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      StackContacts contacts(geo);
      std::vector<double> theta, omega;
      RandomState(n, 0.6, rng, &theta, &omega);
      const double xg = acc(rng), yg = 0.3 * acc(rng);
      const StackSelection sel = contacts.Select(theta.data(), omega.data(), xg, yg);
      std::vector<int> closed;
      Configuration base(n);
      for (int k = 0; k < n; ++k) {
        if (StackContacts::Closed(theta.data(), omega.data(), k)) {
          closed.push_back(k);
        } else {
          const double gap = k == 0 ? theta[0] : theta[k] - theta[k - 1];
          base.set(k, gap > 0 ? Contact::kRight : Contact::kLeft);
        }
      }
      int consistent = 0, total = 1;
      for (size_t i = 0; i < closed.size(); ++i) total *= 3;
      Configuration only;
      for (int code = 0; code < total; ++code) {
        Configuration c = base;
        int rest = code;
        for (const int k : closed) {
          c.set(k, static_cast<Contact>(rest % 3));
          rest /= 3;
        }
        if (contacts.Consistent(c, theta.data(), omega.data(), xg, yg)) {
          ++consistent;
          only = c;
        }
      }
      EXPECT_LE(consistent, 1) << n << " blocks, trial " << trial;
      EXPECT_EQ(sel.consistent, consistent == 1);
      if (consistent == 1) {
        EXPECT_EQ(sel.config, only);
        ++found;
      }
    }
  }
  EXPECT_GT(found, 150);
}

// ---- Impacts ----

TEST(StackContactsTest, TwoBlockImpactsChooseWhatTheThesisModelChooses) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0, 1), rel(0.01, 0.3), rate(0.2, 3.0);
  int compared = 0, settled = 0, inadmissible = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const StackGeometry sg = RandomStack(2, rng);
    const BlockProps &p1 = sg.blocks[0], &p2 = sg.blocks[1];
    const Geometry geo = MakeGeometry(2 * p1.b, 2 * p1.h, p1.m, 2 * p2.b, 2 * p2.h, p2.m, sg.g);
    StackContacts contacts(sg);
    // A mode before, the landing interface, and a state with that gap closed, landing (its
    // rate turns the gap negative).
    const Mode modes[] = {Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b,
                          Mode::k3a, Mode::k3b, Mode::k4a, Mode::k4b};
    const Mode before = modes[trial % 8];
    const Contacts c = ContactsOf(before);
    const bool ground = c.ground != Contact::kFace && (c.interface == Contact::kFace || trial % 3);
    const double s1 = c.ground == Contact::kLeft ? -1 : 1,
                 s2 = c.interface == Contact::kLeft ? -1 : 1;
    State pre;
    if (ground) {
      pre.theta1 = 0.0;
      pre.omega1 = -s1 * rate(rng);
      pre.theta2 = c.interface == Contact::kFace ? 0.0 : s2 * rel(rng);
      pre.omega2 = c.interface == Contact::kFace ? pre.omega1 : pre.omega1 + (unit(rng) - 0.5) * 4;
    } else {
      pre.theta1 = c.ground == Contact::kFace ? 0.0 : s1 * rel(rng);
      pre.omega1 = c.ground == Contact::kFace ? 0.0 : (unit(rng) - 0.5) * 4;
      pre.theta2 = pre.theta1;
      pre.omega2 = pre.omega1 - s2 * rate(rng);
    }
    const double rest_rel = trial % 5 == 0 ? 0.3 : 1e-7;
    const ImpactResult want = ResolveImpact(
        geo, before, pre, ground ? ImpactKind::kGround : ImpactKind::kInterface, rest_rel);
    const double theta[2] = {pre.theta1, pre.theta2}, omega[2] = {pre.omega1, pre.omega2};
    const StackImpact got =
        contacts.ResolveImpact(ConfigurationOf(before, 2), theta, omega, ground ? 0 : 1, rest_rel);
    ++compared;
    settled += want.settled;
    inadmissible += !want.admissible;
    EXPECT_EQ(ConfigurationName(got.chosen.config), ModeName(want.chosen.mode))
        << "trial " << trial << ": " << ModeName(before) << (ground ? " ground" : " interface")
        << " thesis note '" << want.note << "', ours '" << got.note << "'";
    EXPECT_EQ(got.admissible, want.admissible) << trial;
    // impact.h's uniqueness: the thesis's rule evaluates every candidate, and at most one
    // motion passes.
    EXPECT_EQ(want.admissible_outcomes, want.admissible ? 1 : 0) << trial << ": " << want.note;
    EXPECT_EQ(got.settled, want.settled) << trial;
    const double scale = std::abs(pre.omega1) + std::abs(pre.omega2);
    EXPECT_NEAR(got.chosen.omega_radps[0], want.chosen.state.omega1, 1e-12 * scale) << trial;
    EXPECT_NEAR(got.chosen.omega_radps[1], want.chosen.state.omega2, 1e-12 * scale) << trial;
    EXPECT_NEAR(got.energy_before_j, want.energy_before_j, 1e-12 * want.energy_before_j);
    EXPECT_NEAR(got.chosen.energy_after_j, want.chosen.energy_after_j,
                1e-12 * want.energy_before_j);
  }
  std::printf("compared %d impacts: %d settled by the rest rule, %d inadmissible\n", compared,
              settled, inadmissible);
  EXPECT_GT(settled, 50);
}

TEST(StackContactsTest, OneBlockRocksOnOrComesToRestAsHousnersBlockDoes) {
  // e = 1 - 1.5 sin^2(theta_c): positive, the block rocks on about the other corner; negative
  // (a squat block, b/h above about 1.4), no rebound is admissible and it stops.
  for (const double aspect : {0.2, 0.5, 1.0, 2.0}) {
    const double B = 1.0, H = B * aspect;
    const BlockProps p = MakeBlockProps(B, H, 100.0);
    StackContacts contacts(MakeStackGeometry({{B, H, 100.0}}));
    Configuration before(1);
    before.set(0, Contact::kRight);
    const double theta = 0.0, omega = -1.0;
    const StackImpact imp = contacts.ResolveImpact(before, &theta, &omega, 0, 0.0);
    const double e = 1.0 - 1.5 * std::pow(std::sin(p.theta_c), 2);
    if (e > 0) {
      EXPECT_EQ(imp.chosen.config[0], Contact::kLeft) << aspect;
      EXPECT_NEAR(imp.chosen.omega_radps[0], e * omega, 1e-14) << aspect;
    } else {
      EXPECT_TRUE(imp.chosen.config.at_rest()) << aspect;
      EXPECT_EQ(imp.chosen.omega_radps[0], 0.0);
    }
    EXPECT_TRUE(imp.admissible);
  }
}

// A random impact of a random state: interface k lands (its gap closed, the blocks above
// turned with it, with a closing rate); returns k and the configuration before.
int RandomImpact(int n, double p_closed, std::mt19937_64& rng, std::vector<double>* theta_out,
                 std::vector<double>* omega_out, Configuration* before) {
  std::uniform_real_distribution<double> unit(0, 1), rate(0.2, 3.0);
  std::vector<double>& theta = *theta_out;
  std::vector<double>& omega = *omega_out;
  RandomState(n, p_closed, rng, &theta, &omega);
  const int k = static_cast<int>(rng() % n);
  const double shift = (k == 0 ? 0.0 : theta[k - 1]) - theta[k];
  for (int i = k + 1; i < n; ++i) theta[i] += shift;
  // Exactly zero, as the driver lands it.
  theta[k] = k == 0 ? 0.0 : theta[k - 1];
  const Contact side = unit(rng) < 0.5 ? Contact::kRight : Contact::kLeft;
  const double closing = (side == Contact::kRight ? -1 : 1) * rate(rng);
  const double below = k == 0 ? 0.0 : omega[k - 1];
  const double add = below + closing - omega[k];
  for (int i = k; i < n; ++i) omega[i] += add;
  *before = Configuration(n);
  for (int j = 0; j < n; ++j) {
    const double gap = j == 0 ? theta[0] : theta[j] - theta[j - 1];
    if (j == k) {
      before->set(j, side);
    } else if (gap != 0.0) {
      before->set(j, gap > 0 ? Contact::kRight : Contact::kLeft);
    }
  }
  // Closed interfaces above carry their support's rate.
  for (int j = 1; j < n; ++j) {
    if ((*before)[j] == Contact::kFace) omega[j] = omega[j - 1];
  }
  if ((*before)[0] == Contact::kFace) omega[0] = 0.0;
  return k;
}

TEST(StackContactsTest, NoImpactAddsEnergy) {
  std::mt19937_64 rng(12);
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 30; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      StackContacts contacts(geo);
      std::vector<double> theta, omega;
      Configuration before;
      const int k = RandomImpact(n, 0.5, rng, &theta, &omega, &before);
      const StackImpact imp = contacts.ResolveImpact(before, theta.data(), omega.data(), k, 1e-7);
      EXPECT_LE(imp.chosen.energy_after_j,
                imp.energy_before_j + 1e-12 * std::abs(imp.energy_before_j))
          << n << " blocks, " << imp.note;
    }
  }
}

// impact.h's uniqueness argument: at most one motion passes both checks. Every candidate of
// random impacts of random stacks of 1 to 7 blocks (most interfaces closed, so that many
// candidates are in play), and the choice is the one the first-admissible search makes.
TEST(StackContactsTest, AtMostOneImpactMotionIsAdmissible) {
  std::mt19937_64 rng(23);
  int impacts = 0, with_outcome = 0, candidates = 0;
  for (int n = 1; n <= 7; ++n) {
    for (int trial = 0; trial < 150; ++trial) {
      const StackGeometry geo = RandomStack(n, rng);
      StackContacts first(geo), every(geo);
      every.set_exhaustive(true);
      std::vector<double> theta, omega;
      Configuration before;
      const int k = RandomImpact(n, trial % 2 ? 0.8 : 0.5, rng, &theta, &omega, &before);
      const double rest_rel = trial % 3 == 0 ? 0.3 : 1e-7;
      const StackImpact a = first.ResolveImpact(before, theta.data(), omega.data(), k, rest_rel);
      const StackImpact b = every.ResolveImpact(before, theta.data(), omega.data(), k, rest_rel);
      ++impacts;
      with_outcome += b.admissible;
      candidates += b.candidates_tried;
      EXPECT_LE(b.admissible_outcomes, 1) << n << " blocks, trial " << trial << ": " << b.note;
      EXPECT_EQ(b.admissible_outcomes, b.admissible ? 1 : 0) << n << " blocks: " << b.note;
      EXPECT_TRUE(!b.admissible || b.uniqueness_checked);
      EXPECT_FALSE(a.uniqueness_checked);
      EXPECT_EQ(a.admissible, b.admissible);
      EXPECT_EQ(ConfigurationName(a.chosen.config), ConfigurationName(b.chosen.config));
      for (int i = 0; i < n; ++i) EXPECT_EQ(a.chosen.omega_radps[i], b.chosen.omega_radps[i]);
    }
  }
  std::printf("%d impacts, %d with an admissible outcome, %d candidates evaluated\n", impacts,
              with_outcome, candidates);
  // The check has something to find: most impacts have an outcome, among many candidates.
  EXPECT_GT(with_outcome, impacts / 2);
  EXPECT_GT(candidates, 20 * impacts);
}

}  // namespace
}  // namespace rockbench::reference
