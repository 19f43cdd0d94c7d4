// One rigid block (scene/rigid_block.h) and the contact vocabulary of the modes (scene/mode.h):
// closed-form mass properties and energies of a rectangle; every mode's contacts give it back;
// the tilt rule on each side of its thresholds.
#include "scene/rigid_block.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scene/mode.h"

namespace rockbench {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(RigidBlock, MassPropertiesOfARectangle) {
  // B = 1 m, H = 4 m, m = 10,000 kg: b = 0.5, h = 2, r = sqrt(4.25), atan(b / h) = atan(0.25);
  // I_G = m (b^2 + h^2) / 3 and, by the parallel-axis theorem, I_O = I_G + m r^2 = (4/3) m r^2.
  const BlockProps p = MakeBlockProps(1.0, 4.0, 1e4);
  EXPECT_EQ(p.b, 0.5);
  EXPECT_EQ(p.h, 2.0);
  EXPECT_EQ(p.m, 1e4);
  EXPECT_NEAR(p.r, std::sqrt(4.25), 2 * kEps * p.r);
  EXPECT_NEAR(p.theta_c, std::atan(0.25), 2 * kEps);
  EXPECT_NEAR(p.I_G, 1e4 * 4.25 / 3.0, 4 * kEps * p.I_G);
  EXPECT_NEAR(p.I_O, 4.0 / 3.0 * 1e4 * 4.25, 4 * kEps * p.I_O);
}

TEST(RigidBlock, EnergyIsKineticPlusPotential) {
  const BlockProps p = MakeBlockProps(1.0, 4.0, 1e4);
  const double g = 9.81;
  // At rest on its face: m g h.
  EXPECT_NEAR(BlockEnergy_j(p, g, {{0.0, p.h}, {0.0, 0.0}, 0.0}), 1e4 * g * 2.0, 1e-10);
  // Translating at 3 m/s: (1/2) m v^2 more; turning at 2 rad/s: (1/2) I_G w^2 more, either sense.
  EXPECT_NEAR(BlockEnergy_j(p, g, {{0.0, p.h}, {0.0, -3.0}, 0.0}), 1e4 * (g * 2.0 + 4.5), 1e-9);
  EXPECT_NEAR(BlockEnergy_j(p, g, {{0.0, p.h}, {0.0, 0.0}, -2.0}),
              1e4 * g * 2.0 + 0.5 * p.I_G * 4.0, 1e-9);
  // Rocking about its right corner at omega: v_G = omega r, so (1/2) I_O omega^2 of kinetic
  // energy, the corner's own (pure rotation about a fixed point).
  const double omega = 0.7, a = 0.1;  // tilt a about the right corner (x = b, y = 0)
  const Vec2 corner{p.b, 0.0};
  const Vec2 G = corner + Vec2{-p.r * std::sin(p.theta_c - a), p.r * std::cos(p.theta_c - a)};
  const Vec2 vG = -omega * Perp(G - corner);  // clockwise: the counter-clockwise rate is -omega
  EXPECT_NEAR(BlockEnergy_j(p, g, {G, vG, -omega}) - 1e4 * g * G.y, 0.5 * p.I_O * omega * omega,
              1e-9);
}

TEST(ModeContacts, EveryModesContactsGiveItBack) {
  for (const Mode m : {Mode::kRest, Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b, Mode::k3a,
                       Mode::k3b, Mode::k4a, Mode::k4b}) {
    EXPECT_EQ(ModeOf(ContactsOf(m), true), m) << ModeName(m);
  }
  // One block: the interface is ignored (the stack is the block).
  EXPECT_EQ(ModeOf({Contact::kRight, Contact::kLeft}, false), Mode::k3a);
  EXPECT_EQ(ModeOf({Contact::kFace, Contact::kRight}, false), Mode::kRest);
}

TEST(ModeContacts, TiltContactTakesTheAngleThenTheRate) {
  const TiltThresholds thr{1e-5, 1e-2};
  EXPECT_EQ(TiltContact(2e-5, -1.0, thr), Contact::kRight);  // the angle decides
  EXPECT_EQ(TiltContact(-2e-5, 1.0, thr), Contact::kLeft);
  EXPECT_EQ(TiltContact(1e-5, 0.0, thr), Contact::kFace);    // at the threshold: flat, still
  EXPECT_EQ(TiltContact(1e-5, 0.02, thr), Contact::kRight);  // flat, turning: its rate's side
  EXPECT_EQ(TiltContact(0.0, -0.02, thr), Contact::kLeft);
  EXPECT_EQ(TiltContact(0.0, 1e-2, thr), Contact::kFace);  // rate at the threshold: still
  EXPECT_EQ(TiltContact(1e-300, 0.0), Contact::kRight);    // exact states: no thresholds
}

}  // namespace
}  // namespace rockbench
