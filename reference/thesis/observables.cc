#include "reference/thesis/observables.h"

#include <cmath>

#include "reference/thesis/modes.h"

namespace rockbench::reference {

State StateOf(const Sample& sample, bool two_blocks) {
  State st;
  // The top block of the state: block 2, or for one block the block itself.
  const size_t top = two_blocks && sample.theta_rad.size() >= 2 ? 1 : 0;
  st.theta1 = sample.theta_rad[0];
  st.omega1 = sample.omega_radps[0];
  st.theta2 = sample.theta_rad[top];
  st.omega2 = sample.omega_radps[top];
  return st;
}

Mode ModeOfState(const State& s, bool two_blocks, TiltThresholds thresholds) {
  Contacts c;
  c.ground = TiltContact(s.theta1, s.omega1, thresholds);
  c.interface = two_blocks ? TiltContact(s.theta2 - s.theta1, s.omega2 - s.omega1, thresholds)
                           : Contact::kFace;
  return ModeOf(c, two_blocks);
}

MechanicalEnergy StateEnergy(const Geometry& geo, Mode mode, const State& s) {
  return StateEnergy(geo, EvaluateChain(geo, mode, s));
}

MechanicalEnergy StateEnergy(const Geometry& geo, const Chain& ch) {
  const BodyVelocities v = Velocities(ch);
  MechanicalEnergy e;
  e.block1_j = BlockEnergy_j(geo.block1, geo.g, {ch.G[0], v.vG[0], v.w[0]});
  e.total_j = e.block1_j;
  if (geo.two_blocks) {
    e.block2_j = BlockEnergy_j(geo.block2, geo.g, {ch.G[1], v.vG[1], v.w[1]});
    e.total_j += e.block2_j;
  }
  return e;
}

MechanicalEnergy StateEnergy(const Geometry& geo, const State& s) {
  return StateEnergy(geo, ModeOfState(s, geo.two_blocks), s);
}

double EnergyAboveRest_j(const Geometry& geo, const State& s) {
  return StateEnergy(geo, s).total_j - StateEnergy(geo, Mode::kRest, State{}).total_j;
}

// Declared in kinematics.h, beside the other whole-chain quantities.
double Energy(const Geometry& geo, Mode mode, const State& s) {
  return StateEnergy(geo, mode, s).total_j;
}

double RequiredFriction(double normal_n, double tangential_n) {
  return normal_n > 0.0 ? std::abs(tangential_n) / normal_n : 0.0;
}

ContactDemand ContactReactions(const Geometry& geo, Mode mode, const State& s, double xg_mps2,
                               double yg_mps2, Equations equations) {
  const Tilts tilts = TiltsOf(s);
  const auto acc = ModeAccelerations(geo, mode, s, tilts, xg_mps2, yg_mps2, equations);
  return ContactReactions(geo, mode, s, tilts, acc, xg_mps2, yg_mps2);
}

ContactDemand ContactReactions(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts,
                               const std::array<double, 2>& acc, double xg_mps2, double yg_mps2) {
  ContactDemand d;
  d.reactions = ComputeReactions(geo, mode, s, tilts, acc, xg_mps2, yg_mps2);
  d.mu_ground = RequiredFriction(d.reactions.N_ground, d.reactions.T_ground);
  if (geo.two_blocks) {
    d.mu_interface = RequiredFriction(d.reactions.N_interface, d.reactions.T_interface);
  }
  return d;
}

}  // namespace rockbench::reference
