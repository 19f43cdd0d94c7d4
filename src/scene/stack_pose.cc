#include "scene/stack_pose.h"

namespace rockbench {

int PivotSide(double angle_rad, double rate_radps) {
  if (angle_rad > 0.0) return 1;
  if (angle_rad < 0.0) return -1;
  if (rate_radps > 0.0) return 1;
  if (rate_radps < 0.0) return -1;
  return 0;
}

// The engines' initial poses come from here: every operation below is kept as it was in
// engines/common/placement.cc (same operations, same order) so that their histories keep their
// bits.
StackPlacement PlaceStack(double b1, double h1, double b2, double h2, bool two_blocks,
                          const InitialState& s) {
  StackPlacement out;
  const double theta1 = s.theta_rad[0], omega1 = s.omega_radps[0];
  out.ground_side = PivotSide(theta1, omega1);
  const double phi1 = -theta1, w1 = -omega1;
  // Block 1 about its ground pivot P1 (a flat block: any point of the base, take the centre).
  const Vec2 p1{out.ground_side * b1, 0.0};
  const Vec2 g1 = p1 + Rotate(phi1, Vec2{0.0, h1} - Vec2{out.ground_side * b1, 0.0});
  const Vec2 vg1 = Spin(w1, g1 - p1);
  out.block1 = {g1.x, g1.y, phi1, vg1.x, vg1.y, w1};
  if (!two_blocks) return out;

  const double theta2 = s.theta_rad[1], omega2 = s.omega_radps[1];
  out.interface_side = PivotSide(theta2 - theta1, omega2 - omega1);
  const double phi2 = -theta2, w2 = -omega2;
  const double s2b2 = out.interface_side * b2;
  // Block 2's pivot Q2: its base corner on block 1's top face (2 h1 above block 1's base).
  const Vec2 q2 = p1 + Rotate(phi1, Vec2{s2b2, 2.0 * h1} - Vec2{out.ground_side * b1, 0.0});
  const Vec2 g2 = q2 + Rotate(phi2, Vec2{0.0, h2} - Vec2{s2b2, 0.0});
  const Vec2 vq2 = Spin(w1, q2 - p1);
  const Vec2 vg2 = vq2 + Spin(w2, g2 - q2);
  out.block2 = {g2.x, g2.y, phi2, vg2.x, vg2.y, w2};
  return out;
}

StackPlacement PlaceStack(const Scene& scene, const InitialState& state) {
  RequireAtMostTwoBlocks(scene, "stack placement");
  const bool two = scene.block_count() == 2;
  const double b1 = 0.5 * scene.blocks.at(0).width_m, h1 = 0.5 * scene.blocks.at(0).height_m;
  const double b2 = two ? 0.5 * scene.blocks[1].width_m : 0.0;
  const double h2 = two ? 0.5 * scene.blocks[1].height_m : 0.0;
  return PlaceStack(b1, h1, b2, h2, two, state);
}

BlockCorners Corners(const PlanarPose& pose, double b, double h) {
  const Vec2 c{pose.x_m, pose.y_m};
  return {c + Rotate(pose.phi_rad, {-b, -h}), c + Rotate(pose.phi_rad, {b, -h}),
          c + Rotate(pose.phi_rad, {b, h}), c + Rotate(pose.phi_rad, {-b, h})};
}

StackCorners StackCornersAt(const Scene& scene, const InitialState& state) {
  const StackPlacement place = PlaceStack(scene, state);
  StackCorners out;
  const BlockDef& b1 = scene.blocks[0];
  out.block1 = Corners(place.block1, 0.5 * b1.width_m, 0.5 * b1.height_m);
  if (scene.block_count() == 2) {
    const BlockDef& b2 = scene.blocks[1];
    out.has_block2 = true;
    out.block2 = Corners(place.block2, 0.5 * b2.width_m, 0.5 * b2.height_m);
  }
  return out;
}

}  // namespace rockbench
