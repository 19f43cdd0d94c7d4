// The observables of a state (reference/observables.h): the mode rule on constructed states,
// the energy at rest (m g h) and along a free-rocking run between impacts, the reactions at
// rest (the weight) and at the uplift threshold, and the friction those reactions need, each
// against a closed form.
#include "reference/thesis/observables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "motion/ground_motion.h"
#include "reference/simulate.h"

namespace rockbench::reference {
namespace {

constexpr double kG = 9.81;

// The thesis's stack (6.3.1): B1 = H1 = 1.25 m, m1 = 3906.25 kg; B2 = 1 m, H2 = 2.5 m,
// m2 = 6250 kg. Housner's block: B = 1 m, H = 4 m, m = 10000 kg.
Geometry Stack() {
  return MakeGeometry(1.25, 1.25, 3906.25, 1.0, 2.5, 6250.0, kG);
}
Geometry Housner() {
  return MakeGeometry(1.0, 4.0, 10000.0, 0.0, 0.0, 0.0, kG);
}

State Tilted(double theta1, double theta2, double omega1 = 0.0, double omega2 = 0.0) {
  return State{theta1, theta2, omega1, omega2};
}

// ---- Mode ----

TEST(ModeOfState, TiltsPickTheCornerOnTheirSide) {
  EXPECT_EQ(ModeOfState(State{}, true), Mode::kRest);
  EXPECT_EQ(ModeOfState(Tilted(0.1, 0.1), true), Mode::k3a);
  EXPECT_EQ(ModeOfState(Tilted(-0.1, -0.1), true), Mode::k3b);
  EXPECT_EQ(ModeOfState(Tilted(0.1, 0.2), true), Mode::k1a);  // block 2 further right: 1a
  EXPECT_EQ(ModeOfState(Tilted(-0.1, -0.2), true), Mode::k1b);
  EXPECT_EQ(ModeOfState(Tilted(0.1, -0.1), true), Mode::k2a);  // block 2 back on its left
  EXPECT_EQ(ModeOfState(Tilted(-0.1, 0.1), true), Mode::k2b);
  EXPECT_EQ(ModeOfState(Tilted(0.0, 0.1), true), Mode::k4a);  // block 1 flat
  EXPECT_EQ(ModeOfState(Tilted(0.0, -0.1), true), Mode::k4b);
  // Flat but turning: it pivots on the corner of its rate (passing through zero).
  EXPECT_EQ(ModeOfState(Tilted(0.0, 0.0, -0.5, -0.5), true), Mode::k3b);
  EXPECT_EQ(ModeOfState(Tilted(0.0, 0.0, 0.0, 0.5), true), Mode::k4a);
  // One block: the interface is ignored.
  EXPECT_EQ(ModeOfState(Tilted(0.1, 0.3), false), Mode::k3a);
  EXPECT_EQ(ModeOfState(Tilted(0.0, 0.3, 0.0, 1.0), false), Mode::kRest);
}

TEST(ModeOfState, ThresholdsLeaveNoiseFlat) {
  // The engines' monitor's thresholds (MonitorConfig): 1e-5 rad, 1e-2 rad/s.
  const TiltThresholds noisy{1e-5, 1e-2};
  EXPECT_EQ(ModeOfState(Tilted(5e-6, 5e-6, 1e-3, 1e-3), true, noisy), Mode::kRest);
  EXPECT_EQ(ModeOfState(Tilted(5e-6, 5e-6, 1e-3, 1e-3), true), Mode::k3a);       // exact rule
  EXPECT_EQ(ModeOfState(Tilted(5e-6, 5e-6, 0.1, 0.1), true, noisy), Mode::k3a);  // rate decides
  EXPECT_EQ(ModeOfState(Tilted(2e-5, -3e-5, 0.0, 0.0), true, noisy), Mode::k2a);
  // The angle's side decided elsewhere (a hysteresis): the rate only matters when flat.
  EXPECT_EQ(TiltContact(Contact::kRight, -5.0, 1e-2), Contact::kRight);
  EXPECT_EQ(TiltContact(Contact::kFace, -5.0, 1e-2), Contact::kLeft);
  EXPECT_EQ(TiltContact(Contact::kFace, 5e-3, 1e-2), Contact::kFace);
}

// ---- Energy ----

TEST(StateEnergy, AtRestIsTheWeightTimesTheMassCentreHeight) {
  const Geometry one = Housner();
  EXPECT_DOUBLE_EQ(StateEnergy(one, State{}).total_j, 10000.0 * kG * 2.0);
  EXPECT_DOUBLE_EQ(EnergyAboveRest_j(one, State{}), 0.0);
  const Geometry two = Stack();
  const MechanicalEnergy e = StateEnergy(two, State{});
  EXPECT_DOUBLE_EQ(e.block1_j, 3906.25 * kG * 0.625);
  EXPECT_DOUBLE_EQ(e.block2_j, 6250.0 * kG * (1.25 + 1.25));
  EXPECT_DOUBLE_EQ(e.total_j, e.block1_j + e.block2_j);
  EXPECT_DOUBLE_EQ(e.total_j, Energy(two, Mode::kRest, State{}));
}

TEST(StateEnergy, OfARockingBlockIsHousnersClosedForm) {
  // One block rocking about its right corner at theta, omega: the mass centre is at height
  // R cos(theta_c - theta), the kinetic energy (1/2) I_O omega^2 (I_O = (4/3) m R^2).
  const Geometry one = Housner();
  const BlockProps& b = one.block1;
  for (double theta : {0.05, 0.2, -0.1}) {
    for (double omega : {0.0, 0.7, -1.3}) {
      const double expected =
          b.m * kG * b.r * std::cos(b.theta_c - std::abs(theta)) + 0.5 * b.I_O * omega * omega;
      const State s = Tilted(theta, theta, omega, omega);
      EXPECT_NEAR(StateEnergy(one, s).total_j, expected, 1e-12 * expected) << theta << " " << omega;
      EXPECT_NEAR(EnergyAboveRest_j(one, s), expected - b.m * kG * b.h, 1e-10 * expected);
    }
  }
}

TEST(StateEnergy, PerBlockSumsToTheChainsEnergyInEveryMode) {
  const Geometry two = Stack();
  const State s = Tilted(0.07, 0.12, 0.3, -0.4);
  for (Mode mode : {Mode::k1a, Mode::k2a, Mode::k3a, Mode::k4a}) {
    const MechanicalEnergy e = StateEnergy(two, mode, s);
    EXPECT_DOUBLE_EQ(e.total_j, e.block1_j + e.block2_j);
    EXPECT_EQ(e.total_j, Energy(two, mode, s));
  }
  EXPECT_EQ(StateEnergy(two, s).total_j, Energy(two, Mode::k1a, s));  // the mode of the angles
}

// Between impacts free rocking conserves energy; the reference integrates at rtol 1e-12, atol
// 1e-14 (rad, rad/s). Each accepted step's local error is within rtol of the state, and a flight
// between two impacts takes at most a few hundred steps, so the energy drifts by at most ~1e-10
// of its scale M g R (R the stack's corner-to-mass-centre distance): the bound. Measured on
// Housner's block from the written history: 1e-14 of M g R.
void ExpectEnergyConservedBetweenImpacts(const std::string& scene_file) {
  const Scene scene = LoadScene(std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/" + scene_file);
  const Result r = Simulate(scene, GroundMotion::FromScene(scene));
  const Geometry geo = MakeGeometry(scene);
  const double tol = 1e-10 * geo.M * geo.g * geo.R;
  size_t next_event = 0;
  const auto& events = r.history.events;
  double e0 = 0.0;
  bool have_e0 = false;
  int checked = 0;
  for (const Sample& s : r.history.samples) {
    // A sample at an impact's time is the post-impact state: energy starts afresh there.
    bool impact = false;
    while (next_event < events.size() && events[next_event].t_s <= s.t_s) {
      const std::string& k = events[next_event].kind;
      impact = impact || k == "ground_impact" || k == "interface_impact";
      ++next_event;
    }
    const State st = StateOf(s, scene.block_count() == 2);
    const double e = StateEnergy(geo, st).total_j;
    // The mode of the angles and the reference's own mode give the same energy.
    EXPECT_NEAR(StateEnergy(geo, *ModeOfConfiguration(s.mode), st).total_j, e, 1e-12 * e) << s.t_s;
    if (impact || !have_e0) {
      e0 = e;
      have_e0 = true;
      continue;
    }
    EXPECT_NEAR(e, e0, tol) << scene_file << " t = " << s.t_s;
    ++checked;
  }
  EXPECT_GE(checked, 100);
}

TEST(StateEnergy, IsConservedBetweenImpactsOfTheThesisExample) {
  ExpectEnergyConservedBetweenImpacts("thesis_free_rocking.toml");
}

TEST(StateEnergy, IsConservedBetweenImpactsOfHousnersBlock) {
  ExpectEnergyConservedBetweenImpacts("housner_free_rocking.toml");
}

// ---- Reactions and friction ----

TEST(ContactReactions, AtRestOnALevelStillBaseCarryTheWeightWithoutFriction) {
  const Geometry two = Stack();
  const ContactDemand d = ContactReactions(two, Mode::kRest, State{}, 0.0, 0.0);
  const double W = two.M * kG, W2 = two.block2.m * kG;
  EXPECT_NEAR(d.reactions.N_ground, W, 1e-12 * W);
  EXPECT_NEAR(d.reactions.N_interface, W2, 1e-12 * W2);
  EXPECT_NEAR(d.reactions.T_ground, 0.0, 1e-12 * W);
  EXPECT_NEAR(d.reactions.T_interface, 0.0, 1e-12 * W);
  // Centred blocks: each face corner carries half.
  EXPECT_NEAR(d.reactions.ground_left, 0.5 * W, 1e-12 * W);
  EXPECT_NEAR(d.reactions.ground_right, 0.5 * W, 1e-12 * W);
  EXPECT_NEAR(d.mu_ground, 0.0, 1e-12);
  EXPECT_NEAR(d.mu_interface, 0.0, 1e-12);
}

TEST(ContactReactions, AtRestUnderABaseAccelerationNeedFrictionAOverG) {
  // At rest in the base frame every block carries its weight m g and the inertial force m a:
  // |T|/N = a / g at the ground (whole stack) and at the interface (block 2), exactly.
  const Geometry two = Stack();
  const Geometry one = Housner();
  for (double a_g : {0.05, 0.2, -0.3}) {
    const double a = a_g * kG;
    const ContactDemand d = ContactReactions(two, Mode::kRest, State{}, a, 0.0);
    EXPECT_NEAR(d.mu_ground, std::abs(a_g), 1e-12);
    EXPECT_NEAR(d.mu_interface, std::abs(a_g), 1e-12);
    EXPECT_NEAR(d.reactions.N_ground, two.M * kG, 1e-9 * two.M * kG);
    EXPECT_NEAR(ContactReactions(one, Mode::kRest, State{}, a, 0.0).mu_ground, std::abs(a_g),
                1e-12);
    // With a vertical acceleration the normal force is m (g + a_v): |T|/N = a / (g + a_v).
    const ContactDemand v = ContactReactions(two, Mode::kRest, State{}, a, -0.25 * kG);
    EXPECT_NEAR(v.mu_ground, std::abs(a_g) / 0.75, 1e-12);
  }
}

TEST(ContactReactions, AtTheUpliftThresholdTheWholeWeightIsOnOneCorner) {
  // Housner's block at rest under xg'' = -g tan(theta_c) (tipping it to the right): the left
  // corner's force vanishes, the right corner carries m g, and |T|/N = tan(theta_c) = b / h.
  const Geometry one = Housner();
  const BlockProps& b = one.block1;
  const double xg = -kG * b.b / b.h;
  const ContactDemand d = ContactReactions(one, Mode::kRest, State{}, xg, 0.0);
  const double W = b.m * kG;
  EXPECT_NEAR(d.reactions.ground_left, 0.0, 1e-12 * W);
  EXPECT_NEAR(d.reactions.ground_right, W, 1e-12 * W);
  EXPECT_NEAR(d.mu_ground, b.b / b.h, 1e-12);
}

TEST(ContactReactions, OfABlockReleasedTiltedAreHousnersClosedForm) {
  // One block released at rest at theta0 > 0 pivots on its right corner with theta'' =
  // -(m g R / I_O) sin(theta_c - theta0). The mass centre's acceleration gives
  // N = m g (1 - (3/4) sin^2(theta_c - theta0)), |T| = (3/4) m g sin cos(theta_c - theta0).
  const Geometry one = Housner();
  const BlockProps& b = one.block1;
  const double W = b.m * kG;
  for (double theta0 : {0.01, 0.1, 0.2}) {
    const State s = Tilted(theta0, theta0);
    const ContactDemand d = ContactReactions(one, Mode::k3a, s, 0.0, 0.0);
    const double a = b.theta_c - theta0;
    EXPECT_NEAR(d.reactions.N_ground, W * (1.0 - 0.75 * std::sin(a) * std::sin(a)), 1e-12 * W);
    EXPECT_NEAR(std::abs(d.reactions.T_ground), W * 0.75 * std::sin(a) * std::cos(a), 1e-12 * W);
    EXPECT_NEAR(d.mu_ground, std::abs(d.reactions.T_ground) / d.reactions.N_ground, 1e-15);
  }
}

TEST(RequiredFriction, IsTheRatioUnderCompressionAndZeroOtherwise) {
  EXPECT_DOUBLE_EQ(RequiredFriction(100.0, -25.0), 0.25);
  EXPECT_DOUBLE_EQ(RequiredFriction(100.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(RequiredFriction(0.0, 5.0), 0.0);
  EXPECT_DOUBLE_EQ(RequiredFriction(-1.0, 5.0), 0.0);
}

}  // namespace
}  // namespace rockbench::reference
