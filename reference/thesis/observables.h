#pragma once
/// Observables of a state of the two stacked blocks (or of one block): its rocking mode, its
/// mechanical energy, the contact reactions it needs and the friction coefficient those need.
/// One implementation for every user: the reference model (events.csv energies, the validity
/// monitor), the engines' monitor (energy from the bodies' poses, the mode column) and the run
/// report (energy and friction figures).
///
/// Conventions (README, Sign convention): theta > 0 is a tilt to the right, rotating clockwise
/// about the block's right-hand base corner; block 1 is the lower block, block 2 sits centred on
/// it and its tilt on block 1 is theta2 - theta1. Quantities are in the base frame (translating
/// with the ground), origin at block 1's base centre at rest, x right, y up; SI units.
#include <array>

#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "scene/history.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// The state of a history sample (angles rad, rates rad/s). One block: theta2 and omega2 are
/// theta1 and omega1 (the stack is the one block), as the equations of motion expect.
State StateOf(const Sample& sample, bool two_blocks);

// ---- The mode of a state ----

// The tilt's contact rule (scene/mode.h) and a block's energy (scene/rigid_block.h) are the
// scene's, shared with the engines' monitor.
using ::rockbench::BlockEnergy_j;
using ::rockbench::BodyMotion;
using ::rockbench::TiltContact;
using ::rockbench::TiltThresholds;

/// The rocking mode of a state (scene/mode.h): the mode of the contacts TiltContact gives block
/// 1 on the ground and block 2 on block 1 (ModeOf). One block: kRest, k3a or k3b.
/// Examples (thresholds 0): theta1 = theta2 = 0.1 rad: 3a; theta1 = 0.1, theta2 = 0.2: 1a;
/// theta1 = 0.1, theta2 = -0.1: 2a; theta1 = 0, theta2 = -0.1: 4b; all zero: rest.
Mode ModeOfState(const State& state, bool two_blocks, TiltThresholds thresholds = {});

// ---- Mechanical energy ----

/// Energy of a state, J: per block (block2_j is 0 for one block) and their sum.
struct MechanicalEnergy {
  double block1_j = 0.0;
  double block2_j = 0.0;
  double total_j = 0.0;
};
/// Energy of a state moving in `mode` (the pivots the blocks turn about), from the pivot-chain
/// kinematics (kinematics.h). total_j is the value of Energy() and of events.csv's energies.
MechanicalEnergy StateEnergy(const Geometry& geo, Mode mode, const State& state);
/// The same from the chain already evaluated at the state (kinematics.h EvaluateChain).
MechanicalEnergy StateEnergy(const Geometry& geo, const Chain& chain);
/// Energy of a state in the mode ModeOfState gives it (thresholds 0): the energy does not
/// depend on that choice beyond the pivot side of each tilt, which the angles fix.
MechanicalEnergy StateEnergy(const Geometry& geo, const State& state);
/// StateEnergy(geo, state).total_j minus the energy of the stack at rest (sum of m g h_G), J:
/// zero at rest, the work needed to bring the stack from rest to `state`.
double EnergyAboveRest_j(const Geometry& geo, const State& state);

// ---- Contact reactions and the friction they need ----

/// |T| / N, the smallest Coulomb friction coefficient that holds a contact carrying normal
/// force N (compression > 0) and tangential force T, both N; 0 when N <= 0 (no compression:
/// friction cannot hold it, the monitor reports the tension instead). Grows without bound as
/// N -> 0+.
double RequiredFriction(double normal_n, double tangential_n);

/// The contact reactions a state needs in `mode` under base acceleration (xg'', yg'') (m/s^2):
/// the angular accelerations of `mode` (modes.h ModeAccelerations, the thesis's equations of
/// motion) and Newton-Euler on each block (kinematics.h ComputeReactions), and the friction
/// coefficient each contact needs. At rest on a level, still base: N_ground = M g (the total
/// weight), N_interface = m2 g, T = 0, mu = 0; under a base acceleration a at rest: mu = |a| / g.
struct ContactDemand {
  Reactions reactions;        ///< N and T (N) at the ground and the interface, corner forces
  double mu_ground = 0.0;     ///< RequiredFriction at the ground (block 1 on the ground)
  double mu_interface = 0.0;  ///< RequiredFriction at the interface (0 for one block)
};
ContactDemand ContactReactions(const Geometry& geo, Mode mode, const State& state, double xg_mps2,
                               double yg_mps2, Equations equations = Equations::kNonlinear);
/// The same for the mode's accelerations (theta1'', theta2'', rad/s^2) already computed at
/// this state and base motion (an integrator's last stage), with the state's tilts.
ContactDemand ContactReactions(const Geometry& geo, Mode mode, const State& state,
                               const Tilts& tilts, const std::array<double, 2>& acc, double xg_mps2,
                               double yg_mps2);

}  // namespace rockbench::reference
