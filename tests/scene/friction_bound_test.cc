// A block's friction coefficient has an upper bound (issue 38: 1e100 made MuJoCo's state not
// finite): finite values up to 1e4, or inf (and leaving the key out, which is inf). Above 1e4 the
// reference's contact problem treats a friction as infinite, so the bound takes nothing away:
// here the unilateral model at mu = 1e4 and the pivot chain at infinite friction, two different
// formulations, give one motion.
#include <gtest/gtest.h>

#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace rockbench {
namespace {

std::string Error(const std::string& friction, const std::vector<std::string>& overrides = {}) {
  try {
    ParseScene("[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n" + friction, "f.toml",
               overrides);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

const std::string kRange =
    "expected a number from 0 to 10000, or inf (above 1e4 the reference's contact problem treats "
    "a friction as infinite; leave friction out for no slip; docs/limits.md)";

TEST(FrictionBound, FiniteFrictionUpTo1e4OrInfIsAccepted) {
  EXPECT_EQ(Error("friction = 0.0\n"), "no error");
  EXPECT_EQ(Error("friction = 10000.0\n"), "no error");
  EXPECT_EQ(Error("friction = inf\n"), "no error");
  EXPECT_EQ(Error(""), "no error");
}

TEST(FrictionBound, ALargerFrictionIsAnErrorNamingTheKeyAndTheRange) {
  EXPECT_EQ(Error("friction = 1e100\n"), "f.toml:5: block1.friction: " + kRange + ", got 1e+100");
  // The next double above the bound.
  EXPECT_EQ(Error("friction = 10000.000000000002\n"),
            "f.toml:5: block1.friction: " + kRange + ", got 10000.000000000002");
  // Set from the command line (--set), checked again once the overrides are applied.
  const std::string set = Error("", {"block1.friction=1e100"});
  EXPECT_NE(set.find("block1.friction: " + kRange + ", got 1e+100"), std::string::npos) << set;
}

TEST(FrictionBound, AFrictionOf1e4MovesTheBlockAsNoSlipDoes) {
  // Housner's block (1 m x 4 m) released from half its critical angle, 2 s: three impacts.
  const std::string text =
      "[block1]\nwidth = 1.0\nheight = 4.0\ndensity = 2500.0\n%s"
      "[initial]\ntheta1 = 0.12\n[run]\nduration = 2.0\noutput_interval = 0.01\n";
  auto run = [&](const std::string& friction) {
    std::string t = text;
    t.replace(t.find("%s"), 2, friction);
    const Scene s = ParseScene(t, "housner.toml");
    return reference::Simulate(s, GroundMotion::FromScene(s));
  };
  const reference::Result coulomb = run("friction = 1e4\n"), no_slip = run("");
  ASSERT_GT(coulomb.summary.impacts_at[0], 0);
  EXPECT_EQ(coulomb.summary.impacts_at[0], no_slip.summary.impacts_at[0]);
  // The largest |T| / N the contact needed (0.183 measured, below the block's b / h = 0.25):
  // four orders of magnitude below the bound.
  EXPECT_LT(coulomb.summary.friction_required[0], 1.0);
  EXPECT_EQ(coulomb.summary.friction_required[0], no_slip.summary.friction_required[0]);
  // Stick throughout: the same motion, to the bit (no slip was ever decided otherwise).
  double worst = 0.0;
  for (const Sample& s : coulomb.history.samples) {
    const double theta = no_slip.trajectory.At(s.t_s).theta_rad[0];
    worst = std::max(worst, std::abs(s.theta_rad[0] - theta));
  }
  EXPECT_EQ(worst, 0.0);
}

}  // namespace
}  // namespace rockbench
