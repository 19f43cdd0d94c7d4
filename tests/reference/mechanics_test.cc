// The driver's two formulations (reference/mechanics.h) answer alike for two blocks: the
// thesis's explicit equations and the N-block chain, at random states in every mode, to
// rounding (1e-11 relative: the sums involved are of a few O(1) terms, see stack_chain_test).
#include "reference/mechanics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rockbench::reference {
namespace {

Scene TwoBlocks(double B1, double H1, double m1, double B2, double H2, double m2) {
  Scene s;
  s.blocks = {{B1, H1, 1.0, m1, 0.0}, {B2, H2, 1.0, m2, 0.0}};
  return s;
}

constexpr Mode kModes[] = {Mode::kRest, Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b,
                           Mode::k3a,   Mode::k3b, Mode::k4a, Mode::k4b};

Vec4 StateIn(Mode mode, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0.01, 0.4), rate(-2.0, 2.0);
  const Contacts c = ContactsOf(mode);
  Vec4 y{};
  if (c.ground != Contact::kFace) {
    y[0] = (c.ground == Contact::kRight ? 1 : -1) * angle(rng);
    y[2] = rate(rng);
  }
  y[1] = y[0];
  y[3] = y[2];
  if (c.interface != Contact::kFace) {
    y[1] += (c.interface == Contact::kRight ? 1 : -1) * angle(rng);
    y[3] = rate(rng);
  }
  return y;
}

TEST(MechanicsTest, ChainAndThesisAnswerAlikeForTwoBlocks) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> acc(-12.0, 12.0);
  const Scene scenes[] = {TwoBlocks(1.25, 1.25, 3906.25, 1.0, 2.5, 6250.0),
                          TwoBlocks(0.8, 2.0, 3000, 0.8, 0.6, 900)};
  int selections_moving = 0;
  for (const Scene& scene : scenes) {
    const ThesisMechanics thesis(scene);
    const ChainMechanics<2> chain(scene);
    EXPECT_NEAR(chain.time_scale_s(), thesis.time_scale_s(), 1e-15);
    for (const Mode mode : kModes) {
      const Configuration c = ConfigurationOf(mode, 2);
      for (int trial = 0; trial < 25; ++trial) {
        const Vec4 y = StateIn(mode, rng);
        const double xg = acc(rng), yg = 0.3 * acc(rng);
        const Vec4 ft = thesis.Rhs(c, y, xg, yg), fc = chain.Rhs(c, y, xg, yg);
        for (int i = 0; i < 4; ++i) {
          EXPECT_NEAR(fc[i], ft[i], 1e-11 * (1 + std::abs(ft[i]))) << ModeName(mode) << i;
        }
        const auto mt = thesis.Evaluate(c, y, xg, yg);
        const auto mc = chain.Evaluate(c, y, xg, yg);
        EXPECT_NEAR(mc.face, mt.face, 1e-11) << ModeName(mode);
        EXPECT_NEAR(mc.point, mt.point, 1e-11) << ModeName(mode);
        for (int k = 0; k < 2; ++k) {
          EXPECT_NEAR(mc.normal_n[k], mt.normal_n[k], 1e-11 * 1e5) << ModeName(mode) << k;
        }
        EXPECT_NEAR(chain.Energy(c, y), thesis.Energy(c, y), 1e-11 * thesis.Energy(c, y));
        const Vec4 pt = thesis.Project(c, y), pc = chain.Project(c, y);
        for (int i = 0; i < 4; ++i) EXPECT_EQ(pc[i], pt[i]) << ModeName(mode) << i;
        const Selection st = thesis.Select(y, xg, yg), sc = chain.Select(y, xg, yg);
        EXPECT_EQ(sc.consistent, st.consistent);
        if (st.consistent) {
          EXPECT_EQ(sc.config, st.config) << ModeName(mode);
          selections_moving += !st.config.at_rest();
        }
      }
    }
  }
  EXPECT_GT(selections_moving, 100);
}

}  // namespace
}  // namespace rockbench::reference
