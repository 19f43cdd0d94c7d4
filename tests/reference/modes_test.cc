// The thesis's per-mode equations (modes.cc, eqs. 4.23, 4.35, 4.39, 4.42 with OCR typos
// corrected) against the generic pivot-chain Lagrangian assembly (kinematics.cc), at random
// states, in all 8 modes, with and without vertical base acceleration.
#include "reference/thesis/modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "reference/thesis/kinematics.h"

namespace rockbench::reference {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

State RandomState(Mode mode, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0.01, 0.6), rate(-3.0, 3.0);
  State s;
  const double a1 = angle(rng), a2 = angle(rng);
  switch (mode) {
    case Mode::k1a:
      s.theta1 = a1;
      s.theta2 = a1 + a2;
      break;
    case Mode::k1b:
      s.theta1 = -a1;
      s.theta2 = -a1 - a2;
      break;
    case Mode::k2a:
      s.theta1 = a1;
      s.theta2 = a1 - 2 * a2;
      break;
    case Mode::k2b:
      s.theta1 = -a1;
      s.theta2 = -a1 + 2 * a2;
      break;
    case Mode::k3a:
      s.theta1 = s.theta2 = a1;
      break;
    case Mode::k3b:
      s.theta1 = s.theta2 = -a1;
      break;
    case Mode::k4a:
      s.theta2 = a2;
      break;
    case Mode::k4b:
      s.theta2 = -a2;
      break;
    default:
      break;
  }
  s.omega1 = rate(rng);
  s.omega2 = rate(rng);
  if (mode == Mode::k3a || mode == Mode::k3b) s.omega2 = s.omega1;
  if (mode == Mode::k4a || mode == Mode::k4b) s.omega1 = 0.0;
  return s;
}

class ModesTest : public ::testing::TestWithParam<Mode> {};

TEST_P(ModesTest, ThesisEquationsEqualGenericLagrangian) {
  const Mode mode = GetParam();
  std::mt19937_64 rng(1234 + static_cast<int>(mode));
  std::uniform_real_distribution<double> width(0.3, 2.0), slender(0.5, 6.0), dens(500, 8000);
  std::uniform_real_distribution<double> accel(-8.0, 8.0);
  for (int trial = 0; trial < 500; ++trial) {
    const double B1 = width(rng), H1 = B1 * slender(rng);
    const double B2 = B1 * std::uniform_real_distribution<double>(0.2, 1.0)(rng);
    const double H2 = B2 * slender(rng);
    const Geometry geo = MakeGeometry(B1, H1, dens(rng) * B1 * H1, B2, H2, dens(rng) * B2 * H2);
    const State s = RandomState(mode, rng);
    for (bool vertical : {false, true}) {
      const double xg = accel(rng), yg = vertical ? accel(rng) : 0.0;
      const auto thesis = ModeAccelerations(geo, mode, s, xg, yg);
      const auto generic = GenericAccelerations(geo, mode, s, xg, yg);
      // Both solve a 2x2 system built from O(10) terms of size up to ~|M| |acc|: the rounding
      // error is a few ulps times the condition number of the mass matrix.
      const GeneralizedDynamics gd = AssembleDynamics(geo, mode, s, xg, yg);
      double cond = 1.0;
      if (gd.ndof == 2) {
        const double tr = gd.M[0][0] + gd.M[1][1];
        const double det = gd.M[0][0] * gd.M[1][1] - gd.M[0][1] * gd.M[1][0];
        const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
        cond = (tr / 2 + disc) / (tr / 2 - disc);
      }
      const double scale = std::abs(generic[0]) + std::abs(generic[1]) + geo.g / geo.block1.r;
      const double tol = 64 * kEps * cond * scale;
      EXPECT_NEAR(thesis[0], generic[0], tol) << "mode " << ModeName(mode) << " trial " << trial;
      EXPECT_NEAR(thesis[1], generic[1], tol) << "mode " << ModeName(mode) << " trial " << trial;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllModes, ModesTest,
                         ::testing::Values(Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b, Mode::k3a,
                                           Mode::k3b, Mode::k4a, Mode::k4b),
                         [](const auto& info) { return std::string(ModeName(info.param)); });

}  // namespace
}  // namespace rockbench::reference
