#pragma once
/// Where the blocks of the stack are for a state (angles and rates): the pivot chain, defined
/// once for every engine (initial poses, engines/) and the renders (the corners of a frame,
/// renders/). Block 1 turns by theta1 about its base corner on the side of the tilt; block 2,
/// centred on block 1 at rest, sits on block 1's top face at its own pivot corner and turns by
/// theta2 about it (by theta2 - theta1 relative to block 1). Coordinates are the base frame:
/// origin at block 1's base centre at rest, x right, y up, m; phi = -theta is the
/// counter-clockwise angle about +z the engines use (theta > 0 tilts right, clockwise).
#include <array>

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
  PlanarPose block1, block2;  ///< block2 is zero for a single block
  int ground_side = 0;        ///< block 1's pivot: +1 right corner, -1 left, 0 flat
  int interface_side = 0;     ///< block 2's pivot on block 1: +1 right, -1 left, 0 flat
};

/// Pivot of a tilt: +1 (right corner) for a positive angle, -1 for a negative one; a zero angle
/// takes the side of the rate (the block starts rocking that way), 0 when both are zero. A zero
/// angle puts every corner at the same place whichever the side: the side matters for the
/// velocities only.
int PivotSide(double angle_rad, double rate_radps);

/// Places the stack (half widths b, half heights h in m; b2 <= b1, as the scene reader
/// requires). Block 1's pivot side is PivotSide(theta1, omega1); block 2's is
/// PivotSide(theta2 - theta1, omega2 - omega1). Velocities follow the chain:
/// v_G1 = w1 x (G1 - P1), v_G2 = w1 x (Q2 - P1) + w2 x (G2 - Q2).
StackPlacement PlaceStack(double b1_m, double h1_m, double b2_m, double h2_m, bool two_blocks,
                          const InitialState& state);

/// The same for a scene's blocks (b = width / 2, h = height / 2; two blocks when the scene has
/// block 2).
StackPlacement PlaceStack(const Scene& scene, const InitialState& state);

/// The corners of a block counter-clockwise from the bottom-left in its own frame:
/// bottom-left, bottom-right, top-right, top-left, m.
using BlockCorners = std::array<Vec2, 4>;

/// The four corners of a block of half width b and half height h (m) at `pose`.
BlockCorners Corners(const PlanarPose& pose, double b_m, double h_m);

/// The corners of the stack's blocks for a state, in the base frame, m.
struct StackCorners {
  BlockCorners block1{};
  bool has_block2 = false;
  BlockCorners block2{};  ///< valid when has_block2
};

/// The corners of a scene's blocks at `state`, placed by PlaceStack.
StackCorners StackCornersAt(const Scene& scene, const InitialState& state);

}  // namespace rockbench
