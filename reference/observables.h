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

#include "reference/geometry.h"
#include "reference/kinematics.h"
#include "scene/history.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// The state of a history sample (angles rad, rates rad/s). One block: theta2 and omega2 are
/// theta1 and omega1 (the stack is the one block), as the equations of motion expect.
State StateOf(const Sample& sample, bool two_blocks);

// ---- The mode of a state ----

/// Below these a tilt gives no side. Zero (the default) is the rule for exact states, such as
/// the reference's: its closed contacts have exactly zero angle and rate. A noisy state, such as
/// an engine's readout, needs thresholds above its noise (the engines' monitor: MonitorConfig in
/// engines/common/monitor.h, 1e-5 rad to tilt, 5e-6 rad to land, 1e-2 rad/s).
struct TiltThresholds {
  double angle_rad = 0.0;   ///< |angle| at or below this gives no side, rad
  double rate_radps = 0.0;  ///< |rate| at or below this gives no side, rad/s
};

/// The contact of one tilt (block 1 on the ground: theta1, omega1; block 2 on block 1: theta2 -
/// theta1, omega2 - omega1): the right corner when the angle is beyond the threshold to the
/// right, the left corner to the left; a flat block turning faster than the rate threshold
/// pivots on the corner on the side of its rate (it is passing through zero, or starting to
/// rock); flat and still, it sits on its face (Contact::kFace).
Contact TiltContact(double angle_rad, double rate_radps, TiltThresholds thresholds = {});

/// The same rule when the angle's side is already decided (kRight, kLeft, or kFace for flat),
/// for example by a hysteresis on the angle: a flat tilt takes the side of its rate when
/// |rate| > rate_threshold_radps.
Contact TiltContact(Contact angle_side, double rate_radps, double rate_threshold_radps);

/// The rocking mode of a state (scene/mode.h): the mode of the contacts TiltContact gives block
/// 1 on the ground and block 2 on block 1 (ModeOf). One block: kRest, k3a or k3b.
/// Examples (thresholds 0): theta1 = theta2 = 0.1 rad: 3a; theta1 = 0.1, theta2 = 0.2: 1a;
/// theta1 = 0.1, theta2 = -0.1: 2a; theta1 = 0, theta2 = -0.1: 4b; all zero: rest.
Mode ModeOfState(const State& state, bool two_blocks, TiltThresholds thresholds = {});

// ---- Mechanical energy ----

/// The motion of one rigid block in the base frame: mass centre G (m), its velocity (m/s), and
/// the counter-clockwise angular velocity (rad/s; -omega in the thesis's convention).
struct BodyMotion {
  Vec2 G;
  Vec2 vG;
  double w_radps = 0.0;
};

/// Kinetic energy in the base frame plus gravitational potential energy m g y_G of one block,
/// J: (1/2) m |vG|^2 + (1/2) I_G w^2 + m g y_G, with I_G = m (b^2 + h^2) / 3. A block at rest on
/// its face has m g h (h its half height).
double BlockEnergy_j(const BlockProps& block, double g_mps2, const BodyMotion& body);

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
