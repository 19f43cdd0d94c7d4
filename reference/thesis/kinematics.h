#pragma once
/// Generic pivot-chain kinematics and dynamics of the two blocks: positions, Jacobians, mass
/// matrix, forces, contact reactions, energy and angular momentum, for any mode. This is the
/// independent formulation that the thesis's explicit equations (modes.h) and impact laws
/// (impact.h) are checked against, and the Newton-Euler part the validity monitor needs.
/// All quantities are in the base frame (translating with the ground), origin at block 1's
/// base centre at rest, x right, y up.
#include <array>

#include "reference/thesis/geometry.h"
#include "scene/mode.h"
#include "scene/rigid_block.h"

namespace rockbench::reference {

// The plane vector and the contact vocabulary are the scene's (scene/rigid_block.h,
// scene/mode.h), shared with the engines' monitor.
using ::rockbench::Contact;
using ::rockbench::Contacts;
using ::rockbench::ContactsOf;
using ::rockbench::Cross;
using ::rockbench::Dot;
using ::rockbench::ModeOf;
using ::rockbench::Perp;
using ::rockbench::Vec2;

/// State of the two blocks: angles (rad) and rates (rad/s), thesis sign convention.
struct State {
  double theta1 = 0.0, theta2 = 0.0, omega1 = 0.0, omega2 = 0.0;
};

/// Sines and cosines of the two tilts of a state. Every function of the chain needs them;
/// taken once per state and passed down, they are not taken again by each (they were a third
/// of the reference's run time: docs/performance-reference.md).
struct Tilts {
  double sin1 = 0.0, cos1 = 1.0;  ///< of theta1
  double sin2 = 0.0, cos2 = 1.0;  ///< of theta2
};
Tilts TiltsOf(const State& s);

/// Number of degrees of freedom of a mode: 2 (modes 1, 2), 1 (3, 4), 0 (rest).
int DofCount(Mode mode, bool two_blocks);

/// Kinematics of the chain at a state, in a mode.
struct Chain {
  int ndof = 0;
  Vec2 P1;                ///< block 1's ground pivot (for a face: its right corner)
  Vec2 Q2;                ///< block 2's pivot on block 1 (for a face: block 2's corner)
  std::array<Vec2, 2> G;  ///< mass centres of block 1 and block 2
  /// dG_i/du_k and dphi_i/du_k for the mode's generalized rates u (phi = -theta, CCW angle).
  std::array<std::array<Vec2, 2>, 2> JG{};
  std::array<std::array<double, 2>, 2> Jphi{};
  std::array<Vec2, 2> a_vp;   ///< velocity-product (centripetal) accelerations of G_i
  std::array<double, 2> u{};  ///< generalized rates of the mode
  Tilts tilts;                ///< of the state it was evaluated at
};

/// Evaluates the chain. Modes 1/2: u = (omega1, omega2); mode 3: u = omega1 (= omega2);
/// mode 4: u = omega2; rest: none.
Chain EvaluateChain(const Geometry& geo, Mode mode, const State& s);
/// The same with the state's tilts already taken (TiltsOf(s)).
Chain EvaluateChain(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts);

/// Angular accelerations (theta1'', theta2'') of a mode from the generic Lagrangian assembly
/// M(q) u' = J^T (F - M_b a_vp), with effective gravity (-xg'', -(g + yg'')). Mode 3 returns
/// equal values, mode 4 theta1'' = 0, rest zeros.
std::array<double, 2> GenericAccelerations(const Geometry& geo, Mode mode, const State& s,
                                           double xg_mps2, double yg_mps2);

/// Mass matrix M = J^T M_b J (ndof x ndof, row-major in a 2x2 array) and generalized force.
struct GeneralizedDynamics {
  int ndof = 0;
  double M[2][2] = {{0, 0}, {0, 0}};
  double f[2] = {0, 0};
};
GeneralizedDynamics AssembleDynamics(const Geometry& geo, Mode mode, const State& s, double xg_mps2,
                                     double yg_mps2);

/// Contact reactions on the blocks: ground on block 1, block 1 on block 2. N is the normal
/// component (positive = compression), T the tangential one along the face (positive +x of the
/// face). A face contact is split into the normal forces at its two corners (left, right).
struct Reactions {
  double N_ground = 0.0, T_ground = 0.0;               ///< N
  double N_interface = 0.0, T_interface = 0.0;         ///< N
  double ground_left = 0.0, ground_right = 0.0;        ///< corner normal forces (face only)
  double interface_left = 0.0, interface_right = 0.0;  ///< corner normal forces (face only)
};
/// Reactions for given accelerations (theta1'', theta2'') consistent with the mode.
Reactions ComputeReactions(const Geometry& geo, Mode mode, const State& s,
                           const std::array<double, 2>& acc, double xg_mps2, double yg_mps2);
/// The same with the state's tilts already taken (TiltsOf(s)).
Reactions ComputeReactions(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts,
                           const std::array<double, 2>& acc, double xg_mps2, double yg_mps2);

/// Mass-centre velocities and CCW angular velocities of the two blocks.
struct BodyVelocities {
  std::array<Vec2, 2> vG{};
  std::array<double, 2> w{};
};
BodyVelocities Velocities(const Geometry& geo, Mode mode, const State& s);
/// The same from the chain already evaluated at the state.
BodyVelocities Velocities(const Chain& ch);

/// Contact loads (ground on block 1, block 1 on block 2) that give the blocks mass-centre
/// accelerations aG and CCW angular accelerations alpha under effective gravity g_eff. With
/// velocity jumps in place of accelerations and g_eff = 0 it gives the impact impulses.
Reactions ContactLoads(const Geometry& geo, Mode mode, const State& s,
                       const std::array<Vec2, 2>& aG, const std::array<double, 2>& alpha,
                       Vec2 g_eff);
/// The same with the state's tilts already taken (TiltsOf(s)).
Reactions ContactLoads(const Geometry& geo, Mode mode, const Tilts& tilts,
                       const std::array<Vec2, 2>& aG, const std::array<double, 2>& alpha,
                       Vec2 g_eff);

/// Kinetic energy in the base frame plus gravitational potential m g y_G, J: StateEnergy(geo,
/// mode, s).total_j (observables.h, where it is defined with the energy of each block).
double Energy(const Geometry& geo, Mode mode, const State& s);
/// Angular momentum about point A (base frame) of block `body` (0 or 1) or of both (-1),
/// counter-clockwise positive, kg m^2/s.
double AngularMomentum(const Geometry& geo, Mode mode, const State& s, Vec2 A, int body);

/// World positions of the four corners of each block (bottom-left, bottom-right, top-right,
/// top-left) in the base frame, for renderers and engines' placement checks.
std::array<std::array<Vec2, 4>, 2> BlockCorners(const Geometry& geo, Mode mode, const State& s);

}  // namespace rockbench::reference
