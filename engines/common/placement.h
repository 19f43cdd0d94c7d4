#pragma once
/// Planar placement of the blocks from the thesis's state (angles and rates) by the pivot chain:
/// block 1 rotated by theta1 about its base corner on the side of the tilt, block 2 placed on
/// block 1's top face at its pivot corner and rotated by theta2 about it. Coordinates are the
/// base frame: origin at block 1's base centre at rest, x right, y up; phi = -theta is the
/// counter-clockwise angle about +z the engines use.
#include <array>

#include "scene/scene.h"

namespace rockbench {

struct Point2 {
  double x = 0.0, y = 0.0;
};

/// A block's planar pose and velocity: mass centre (m), CCW angle phi (rad), centre velocity
/// (m/s) and CCW angular velocity w (rad/s).
struct PlanarPose {
  double x_m = 0.0, y_m = 0.0, phi_rad = 0.0;
  double vx_mps = 0.0, vy_mps = 0.0, w_radps = 0.0;
};

struct StackPlacement {
  PlanarPose block1, block2;  ///< block2 is zero for a single block
  int ground_side = 0;        ///< block 1's pivot: +1 right corner, -1 left, 0 flat
  int interface_side = 0;     ///< block 2's pivot on block 1: +1 right, -1 left, 0 flat
};

/// Pivot of a tilt: +1 (right corner) for a positive angle, -1 for a negative one; a zero angle
/// takes the side of the rate (the block starts rocking that way), 0 when both are zero.
int PivotSide(double angle_rad, double rate_radps);

/// Places the stack (half widths b, half heights h in m). Block 1's pivot side is
/// PivotSide(theta1, omega1); block 2's is PivotSide(theta2 - theta1, omega2 - omega1).
/// Velocities follow the chain: v_G1 = w1 x (G1 - P1), v_G2 = w1 x (Q2 - P1) + w2 x (G2 - Q2).
StackPlacement PlaceStack(double b1_m, double h1_m, double b2_m, double h2_m, bool two_blocks,
                          const InitialState& state);

/// The four corners of a block of half width b and half height h at `pose`, in the order
/// bottom-left, bottom-right, top-right, top-left.
std::array<Point2, 4> Corners(const PlanarPose& pose, double b_m, double h_m);

}  // namespace rockbench
