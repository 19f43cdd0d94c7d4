#include "scene/cylinder_state.h"

#include <cmath>
#include <numbers>

namespace rockbench {
namespace {

constexpr double kPi = std::numbers::pi;

// The tilt frame (docs/cylinder-3d.md section 0): e1 down the slope in the bottom face, e2 the
// horizontal tilt axis, e3 the cylinder's axis.
struct TiltFrame {
  Vec3d e1, e2, e3;
};
TiltFrame FrameOf(double tilt_rad, double azimuth_rad) {
  const double st = std::sin(tilt_rad), ct = std::cos(tilt_rad);
  const double sp = std::sin(azimuth_rad), cp = std::cos(azimuth_rad);
  return {{ct * cp, ct * sp, -st}, {-sp, cp, 0.0}, {st * cp, st * sp, ct}};
}

double Dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// `angle` moved by a whole number of turns to lie within pi of `near`.
double Unwrapped(double angle, double near) {
  return angle + 2.0 * kPi * std::round((near - angle) / (2.0 * kPi));
}

}  // namespace

double CylinderState::tilt_x_rad() const {
  return tilt_rad * std::cos(azimuth_rad);
}
double CylinderState::tilt_y_rad() const {
  return tilt_rad * std::sin(azimuth_rad);
}

Mat3d CylinderRotation(const CylinderState& s) {
  const double st = std::sin(s.tilt_rad), ct = std::cos(s.tilt_rad);
  const double sp = std::sin(s.azimuth_rad), cp = std::cos(s.azimuth_rad);
  const double ss = std::sin(s.spin_rad), cs = std::cos(s.spin_rad);
  // Rz(azimuth) Ry(tilt) Rz(spin).
  return {cp * ct * cs - sp * ss,
          -cp * ct * ss - sp * cs,
          cp * st,
          sp * ct * cs + cp * ss,
          -sp * ct * ss + cp * cs,
          sp * st,
          -st * cs,
          st * ss,
          ct};
}

Vec3d CylinderAngularVelocity(const CylinderState& s) {
  // Frame components (-azimuth' sin tilt, tilt', spin' + azimuth' cos tilt).
  const TiltFrame f = FrameOf(s.tilt_rad, s.azimuth_rad);
  const double w1 = -s.azimuth_rate_radps * std::sin(s.tilt_rad);
  const double w2 = s.tilt_rate_radps;
  const double w3 = s.spin_rate_radps + s.azimuth_rate_radps * std::cos(s.tilt_rad);
  Vec3d w;
  for (int i = 0; i < 3; ++i) w[i] = w1 * f.e1[i] + w2 * f.e2[i] + w3 * f.e3[i];
  return w;
}

CylinderState CylinderStateOf(const Mat3d& q, const Vec3d& omega, const CylinderState* previous) {
  CylinderState s;
  // The axis is the third column.
  const double kx = q[2], ky = q[5], kz = q[8];
  const double horizontal = std::hypot(kx, ky);
  s.tilt_rad = std::atan2(horizontal, kz);
  const bool upright = std::sin(s.tilt_rad) < 1e-12;
  if (!upright) {
    s.azimuth_rad = std::atan2(ky, kx);
    s.spin_rad = std::atan2(q[7], -q[6]);
  } else {
    // Only azimuth + spin has a value: keep the azimuth.
    s.azimuth_rad = previous ? previous->azimuth_rad : 0.0;
    s.spin_rad = std::atan2(q[3], q[0]) - s.azimuth_rad;
  }
  if (previous) {
    s.azimuth_rad = Unwrapped(s.azimuth_rad, previous->azimuth_rad);
    s.spin_rad = Unwrapped(s.spin_rad, previous->spin_rad);
  }
  const TiltFrame f = FrameOf(s.tilt_rad, s.azimuth_rad);
  s.tilt_rate_radps = Dot(omega, f.e2);
  const double w3 = Dot(omega, f.e3);
  if (!upright) {
    s.azimuth_rate_radps = -Dot(omega, f.e1) / std::sin(s.tilt_rad);
    s.spin_rate_radps = w3 - s.azimuth_rate_radps * std::cos(s.tilt_rad);
  } else {
    s.spin_rate_radps = w3;
  }
  return s;
}

Vec3d CylinderCentre(const CylinderState& s, double radius_m, double half_height_m) {
  const TiltFrame f = FrameOf(s.tilt_rad, s.azimuth_rad);
  // Contact point on the base, then the centre at -R e1 + h e3 from it.
  const double cp = std::cos(s.azimuth_rad), sp = std::sin(s.azimuth_rad);
  Vec3d c{radius_m * cp, radius_m * sp, 0.0};
  for (int i = 0; i < 3; ++i) c[i] += -radius_m * f.e1[i] + half_height_m * f.e3[i];
  return c;
}

Vec3d CylinderCentreVelocity(const CylinderState& s, double radius_m, double half_height_m) {
  const TiltFrame f = FrameOf(s.tilt_rad, s.azimuth_rad);
  const Vec3d w = CylinderAngularVelocity(s);
  Vec3d r;
  for (int i = 0; i < 3; ++i) r[i] = -radius_m * f.e1[i] + half_height_m * f.e3[i];
  return {w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]};
}

}  // namespace rockbench
