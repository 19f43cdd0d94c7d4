#include "scene/stack_pose.h"

#include <stdexcept>
#include <string>

namespace rockbench {
namespace {

// The chain over n blocks of half widths b[k] and half heights h[k].
//
// The engines' initial poses come from here: for one and two blocks every operation below is
// the one engines/common/placement.cc made (the same operations in the same order, with no
// term added for P_1's velocity, which is zero), so that their histories keep their bits.
StackPlacement PlaceChain(const double* b, const double* h, int n, const InitialState& s) {
  if (n < 1 || n > kMaxBlocks) {
    throw std::invalid_argument(std::string("PlaceStack: ") + std::to_string(n) +
                                " blocks; expected 1 to " + std::to_string(kMaxBlocks));
  }
  StackPlacement out;
  out.blocks.resize(static_cast<size_t>(n));
  out.sides.resize(static_cast<size_t>(n));
  Vec2 p, vp;  // block k's pivot P_k and its velocity (v_P1 = 0: not added)
  for (int k = 0; k < n; ++k) {
    const double theta = s.theta_rad[k], omega = s.omega_radps[k];
    const int side = k == 0 ? PivotSide(theta, omega)
                            : PivotSide(theta - s.theta_rad[k - 1], omega - s.omega_radps[k - 1]);
    const double sb = side * b[k];
    if (k > 0) {
      // P_(k+1) from block k's pivot: its base corner on block k's top face (2 h_k above
      // block k's base), carried by block k's turn.
      const double phi_below = -s.theta_rad[k - 1], w_below = -s.omega_radps[k - 1];
      const double sb_below = out.sides[k - 1] * b[k - 1];
      const Vec2 q = p + Rotate(phi_below, Vec2{sb, 2.0 * h[k - 1]} - Vec2{sb_below, 0.0});
      vp = k == 1 ? Spin(w_below, q - p) : vp + Spin(w_below, q - p);
      p = q;
    } else {
      // Block 1 about its ground pivot P1 (a flat block: any point of the base, take the centre).
      p = Vec2{sb, 0.0};
    }
    const double phi = -theta, w = -omega;
    const Vec2 g = p + Rotate(phi, Vec2{0.0, h[k]} - Vec2{sb, 0.0});
    const Vec2 vg = k == 0 ? Spin(w, g - p) : vp + Spin(w, g - p);
    out.sides[k] = side;
    out.blocks[k] = {g.x, g.y, phi, vg.x, vg.y, w};
  }
  return out;
}

}  // namespace

int PivotSide(double angle_rad, double rate_radps) {
  if (angle_rad > 0.0) return 1;
  if (angle_rad < 0.0) return -1;
  if (rate_radps > 0.0) return 1;
  if (rate_radps < 0.0) return -1;
  return 0;
}

StackPlacement PlaceStack(const std::vector<BlockDef>& blocks, const InitialState& state) {
  const int n = static_cast<int>(blocks.size());
  if (n < 1 || n > kMaxBlocks) return PlaceChain(nullptr, nullptr, n, state);  // throws
  std::array<double, kMaxBlocks> b{}, h{};
  for (int k = 0; k < n; ++k) {
    b[k] = 0.5 * blocks[k].width_m;
    h[k] = 0.5 * blocks[k].height_m;
  }
  return PlaceChain(b.data(), h.data(), n, state);
}

StackPlacement PlaceStack(const Scene& scene, const InitialState& state) {
  return PlaceStack(scene.blocks, state);
}

BlockCorners Corners(const PlanarPose& pose, double b, double h) {
  const Vec2 c{pose.x_m, pose.y_m};
  return {c + Rotate(pose.phi_rad, {-b, -h}), c + Rotate(pose.phi_rad, {b, -h}),
          c + Rotate(pose.phi_rad, {b, h}), c + Rotate(pose.phi_rad, {-b, h})};
}

StackCorners StackCornersAt(const Scene& scene, const InitialState& state) {
  const StackPlacement place = PlaceStack(scene, state);
  StackCorners out;
  out.blocks.reserve(place.blocks.size());
  for (size_t k = 0; k < place.blocks.size(); ++k) {
    const BlockDef& def = scene.blocks[k];
    out.blocks.push_back(Corners(place.blocks[k], 0.5 * def.width_m, 0.5 * def.height_m));
  }
  return out;
}

}  // namespace rockbench
