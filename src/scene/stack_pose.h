#pragma once
/// Where the blocks of the stack are for a state (angles and rates): the pivot chain of N blocks
/// (docs/n-blocks.md), defined once for every engine (initial poses, engines/, the external
/// engines' input), the monitor and the renders (the corners of a frame, renders/). The
/// reference keeps its own pivots (reference/thesis/kinematics.cc, reference/chain/): they are
/// the model's equations, not a placement. Block 1 turns by theta1 about its base corner on the
/// side of its tilt; block k + 1, centred on block k at rest, sits on block k's top face at its own
/// pivot corner and turns by theta_(k+1) about it (by theta_(k+1) - theta_k relative to block
/// k). Coordinates are the base frame: origin at block 1's base centre at rest, x right, y up,
/// m; phi = -theta is the counter-clockwise angle about +z the engines use (theta > 0 tilts
/// right, clockwise).
#include <array>
#include <vector>

#include "scene/scene.h"
#include "scene/vec2.h"

namespace rockbench {

/// A block's planar pose and velocity: mass centre (m), CCW angle phi (rad), centre velocity
/// (m/s) and CCW angular velocity w (rad/s).
struct PlanarPose {
  double x_m = 0.0, y_m = 0.0, phi_rad = 0.0;
  double vx_mps = 0.0, vy_mps = 0.0, w_radps = 0.0;
};

/// The poses of the stack's blocks and the pivots the chain chose.
struct StackPlacement {
  /// Block k's pose at index k - 1, bottom first: one per block.
  std::vector<PlanarPose> blocks;
  /// Interface k's pivot at index k - 1 (block 1 on the ground, block k on block k - 1):
  /// +1 block k's right base corner, -1 its left one, 0 flat (on its face).
  std::vector<int> sides;
};

/// Pivot of a tilt: +1 (right corner) for a positive angle, -1 for a negative one; a zero angle
/// takes the side of the rate (the block starts rocking that way), 0 when both are zero. A zero
/// angle puts every corner at the same place whichever the side: the side matters for the
/// velocities only.
int PivotSide(double angle_rad, double rate_radps);

/// Places a stack of N = blocks.size() blocks (1..kMaxBlocks; each no wider than the one below,
/// as the scene reader requires; b = width / 2, h = height / 2). Interface k's pivot side is
/// PivotSide(theta_k - theta_(k-1), omega_k - omega_(k-1)) (theta_0 = omega_0 = 0: the
/// ground). With s_k that side and phi_k = -theta_k:
///   P_1 = (s_1 b_1, 0),
///   P_(k+1) = P_k + R(phi_k) ((s_(k+1) b_(k+1), 2 h_k) - (s_k b_k, 0)),
///   G_k = P_k + R(phi_k) ((0, h_k) - (s_k b_k, 0)),
///   v_P(k+1) = v_Pk + w_k x (P_(k+1) - P_k),  v_Gk = v_Pk + w_k x (G_k - P_k),  v_P1 = 0,
/// with w_k = -omega_k. A flat interface (side 0) puts block k's pivot at the middle of its
/// base. Throws std::invalid_argument for no block or more than kMaxBlocks.
StackPlacement PlaceStack(const std::vector<BlockDef>& blocks, const InitialState& state);

/// The same for a scene's blocks.
StackPlacement PlaceStack(const Scene& scene, const InitialState& state);

/// The corners of a block counter-clockwise from the bottom-left in its own frame:
/// bottom-left, bottom-right, top-right, top-left, m.
using BlockCorners = std::array<Vec2, 4>;

/// The four corners of a block of half width b and half height h (m) at `pose`.
BlockCorners Corners(const PlanarPose& pose, double b_m, double h_m);

/// The corners of the stack's blocks for a state, in the base frame, m.
struct StackCorners {
  /// Block k's corners at index k - 1, bottom first: one per block.
  std::vector<BlockCorners> blocks;
};

/// The corners of a scene's blocks at `state`, placed by PlaceStack (every block of the scene).
StackCorners StackCornersAt(const Scene& scene, const InitialState& state);

}  // namespace rockbench
