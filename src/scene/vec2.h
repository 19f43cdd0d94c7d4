#pragma once
/// The one vector of the plane of motion that the whole program shares: the reference's
/// kinematics, the engines' placement of the blocks, the monitor, and the renders' corners and
/// pixels. x right, y up (pixels: x right, y down); the unit is the use's (m, m/s, N, px).

#include <cmath>

namespace rockbench {

/// A vector (or point) of the plane (m, m/s, N or px, by use).
struct Vec2 {
  double x = 0.0, y = 0.0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(double s, Vec2 a) {
  return {s * a.x, s * a.y};
}
inline double Dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double Cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
/// a rotated by +90 degrees (counter-clockwise).
inline Vec2 Perp(Vec2 a) {
  return {-a.y, a.x};
}
/// a rotated counter-clockwise by phi_rad (for a block: phi = -theta, the thesis's clockwise
/// tilt).
inline Vec2 Rotate(double phi_rad, Vec2 a) {
  const double c = std::cos(phi_rad), s = std::sin(phi_rad);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}
/// The velocity of a point at offset r (m) from a pivot turning at the counter-clockwise rate
/// w_radps: w x r, m/s.
inline Vec2 Spin(double w_radps, Vec2 r) {
  return {-w_radps * r.y, w_radps * r.x};
}

}  // namespace rockbench
