#include "engines/common/placement.h"

#include <cmath>

namespace rockbench {
namespace {

Point2 Rotate(double phi, Point2 v) {
  const double c = std::cos(phi), s = std::sin(phi);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}
Point2 Add(Point2 a, Point2 b) {
  return {a.x + b.x, a.y + b.y};
}
Point2 Sub(Point2 a, Point2 b) {
  return {a.x - b.x, a.y - b.y};
}
// Velocity of a point at offset r from a pivot turning at CCW rate w: w x r.
Point2 Spin(double w, Point2 r) {
  return {-w * r.y, w * r.x};
}

}  // namespace

int PivotSide(double angle_rad, double rate_radps) {
  if (angle_rad > 0.0) return 1;
  if (angle_rad < 0.0) return -1;
  if (rate_radps > 0.0) return 1;
  if (rate_radps < 0.0) return -1;
  return 0;
}

StackPlacement PlaceStack(double b1, double h1, double b2, double h2, bool two_blocks,
                          const InitialState& s) {
  StackPlacement out;
  out.ground_side = PivotSide(s.theta1_rad, s.omega1_radps);
  const double phi1 = -s.theta1_rad, w1 = -s.omega1_radps;
  // Block 1 about its ground pivot P1 (a flat block: any point of the base, take the centre).
  const Point2 p1{out.ground_side * b1, 0.0};
  const Point2 g1 = Add(p1, Rotate(phi1, Sub(Point2{0.0, h1}, Point2{out.ground_side * b1, 0.0})));
  const Point2 vg1 = Spin(w1, Sub(g1, p1));
  out.block1 = {g1.x, g1.y, phi1, vg1.x, vg1.y, w1};
  if (!two_blocks) return out;

  out.interface_side = PivotSide(s.theta2_rad - s.theta1_rad, s.omega2_radps - s.omega1_radps);
  const double phi2 = -s.theta2_rad, w2 = -s.omega2_radps;
  const double s2b2 = out.interface_side * b2;
  // Block 2's pivot Q2: its base corner on block 1's top face (2 h1 above block 1's base).
  const Point2 q2 =
      Add(p1, Rotate(phi1, Sub(Point2{s2b2, 2.0 * h1}, Point2{out.ground_side * b1, 0.0})));
  const Point2 g2 = Add(q2, Rotate(phi2, Sub(Point2{0.0, h2}, Point2{s2b2, 0.0})));
  const Point2 vq2 = Spin(w1, Sub(q2, p1));
  const Point2 vg2 = Add(vq2, Spin(w2, Sub(g2, q2)));
  out.block2 = {g2.x, g2.y, phi2, vg2.x, vg2.y, w2};
  return out;
}

std::array<Point2, 4> Corners(const PlanarPose& pose, double b, double h) {
  const Point2 c{pose.x_m, pose.y_m};
  return {Add(c, Rotate(pose.phi_rad, {-b, -h})), Add(c, Rotate(pose.phi_rad, {b, -h})),
          Add(c, Rotate(pose.phi_rad, {b, h})), Add(c, Rotate(pose.phi_rad, {-b, h}))};
}

}  // namespace rockbench
