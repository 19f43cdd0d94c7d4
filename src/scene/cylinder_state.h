#pragma once
/// What a cylinder's history columns mean (shape "cylinder", docs/three-d.md): its orientation
/// as ZYZ Euler angles Q = Rz(azimuth) Ry(tilt) Rz(spin) (world axes: +x along
/// [base.horizontal], +y along [base.transverse], +z up), the rates of those angles, and the
/// pose of a cylinder standing on the rim point on the side it leans toward. One conversion for
/// the reference, every engine and the renders.
#include <array>
#include <cmath>
#include <numbers>

namespace rockbench {

/// 3-vector and row-major 3x3 matrix, world or body components as stated.
using Vec3d = std::array<double, 3>;
using Mat3d = std::array<double, 9>;

/// A cylinder's state: the tilt of its axis from vertical (>= 0), the azimuth toward which its
/// top leans (from +x toward +y), the spin about its axis, and their rates.
struct CylinderState {
  double tilt_rad = 0.0;
  double azimuth_rad = 0.0;
  double spin_rad = 0.0;
  double tilt_rate_radps = 0.0;
  double azimuth_rate_radps = 0.0;
  double spin_rate_radps = 0.0;
  /// tilt cos(azimuth) and tilt sin(azimuth), rad: the tilt vector, continuous through upright.
  /// tilt_x > 0 is a lean toward +x (the planar model's theta > 0 in the planar limit).
  double tilt_x_rad() const;
  double tilt_y_rad() const;
};

/// The rotation body -> world (row-major) of a state's angles: its columns are the body axes,
/// the third one the cylinder's axis.
Mat3d CylinderRotation(const CylinderState& state);
/// The angular velocity, world components, rad/s, of a state's angles and rates.
Vec3d CylinderAngularVelocity(const CylinderState& state);

/// An azimuth as summaries and a landing's new lean give it: the same direction within (-pi, pi].
double WrappedAzimuth_rad(double azimuth_rad);

/// The state of a rotation (row-major, body -> world, body z the axis) and angular velocity
/// (world, rad/s). `previous`, when given, is the state one output earlier: the azimuth and spin
/// are unwrapped to be continuous with it (within pi), and an upright pose (sin tilt below
/// 1e-12, where the azimuth has no value) keeps its azimuth and reports a zero azimuth rate.
CylinderState CylinderStateOf(const Mat3d& rotation, const Vec3d& omega_world_radps,
                              const CylinderState* previous = nullptr);

/// Where a cylinder of radius `radius_m` and half-height `half_height_m` has its centre when it
/// leans at `state`'s tilt and azimuth on the rim point that lay at (R cos azimuth, R sin
/// azimuth, 0) when it stood upright centred on the origin: the rim point stays on the base
/// (world, m).
Vec3d CylinderCentre(const CylinderState& state, double radius_m, double half_height_m);
/// The velocity of that centre (world, m/s) when the cylinder rolls without slipping on that rim
/// point at `state`'s rates: omega x (centre - contact point).
Vec3d CylinderCentreVelocity(const CylinderState& state, double radius_m, double half_height_m);

// The definitions, inline (the vocabulary's folder holds its headers and readers).

namespace cylinder_state_detail {

inline constexpr double kPi = std::numbers::pi;

// The tilt frame (docs/cylinder-3d.md section 0): e1 down the slope in the bottom face, e2 the
// horizontal tilt axis, e3 the cylinder's axis.
struct TiltFrame {
  Vec3d e1, e2, e3;
};
inline TiltFrame FrameOf(double tilt_rad, double azimuth_rad) {
  const double st = std::sin(tilt_rad), ct = std::cos(tilt_rad);
  const double sp = std::sin(azimuth_rad), cp = std::cos(azimuth_rad);
  return {{ct * cp, ct * sp, -st}, {-sp, cp, 0.0}, {st * cp, st * sp, ct}};
}

inline double Dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// `angle` moved by a whole number of turns to lie within pi of `near`.
inline double Unwrapped(double angle, double near) {
  return angle + 2.0 * kPi * std::round((near - angle) / (2.0 * kPi));
}

}  // namespace cylinder_state_detail

inline double WrappedAzimuth_rad(double azimuth_rad) {
  const double a = std::remainder(azimuth_rad, 2.0 * cylinder_state_detail::kPi);
  return a <= -cylinder_state_detail::kPi ? a + 2.0 * cylinder_state_detail::kPi : a;
}

inline double CylinderState::tilt_x_rad() const {
  return tilt_rad * std::cos(azimuth_rad);
}
inline double CylinderState::tilt_y_rad() const {
  return tilt_rad * std::sin(azimuth_rad);
}

inline Mat3d CylinderRotation(const CylinderState& s) {
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

inline Vec3d CylinderAngularVelocity(const CylinderState& s) {
  // Frame components (-azimuth' sin tilt, tilt', spin' + azimuth' cos tilt).
  const cylinder_state_detail::TiltFrame f =
      cylinder_state_detail::FrameOf(s.tilt_rad, s.azimuth_rad);
  const double w1 = -s.azimuth_rate_radps * std::sin(s.tilt_rad);
  const double w2 = s.tilt_rate_radps;
  const double w3 = s.spin_rate_radps + s.azimuth_rate_radps * std::cos(s.tilt_rad);
  Vec3d w;
  for (int i = 0; i < 3; ++i) w[i] = w1 * f.e1[i] + w2 * f.e2[i] + w3 * f.e3[i];
  return w;
}

inline CylinderState CylinderStateOf(const Mat3d& q, const Vec3d& omega,
                                     const CylinderState* previous) {
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
    s.azimuth_rad = cylinder_state_detail::Unwrapped(s.azimuth_rad, previous->azimuth_rad);
    s.spin_rad = cylinder_state_detail::Unwrapped(s.spin_rad, previous->spin_rad);
  }
  const cylinder_state_detail::TiltFrame f =
      cylinder_state_detail::FrameOf(s.tilt_rad, s.azimuth_rad);
  s.tilt_rate_radps = cylinder_state_detail::Dot(omega, f.e2);
  const double w3 = cylinder_state_detail::Dot(omega, f.e3);
  if (!upright) {
    s.azimuth_rate_radps = -cylinder_state_detail::Dot(omega, f.e1) / std::sin(s.tilt_rad);
    s.spin_rate_radps = w3 - s.azimuth_rate_radps * std::cos(s.tilt_rad);
  } else {
    s.spin_rate_radps = w3;
  }
  return s;
}

inline Vec3d CylinderCentre(const CylinderState& s, double radius_m, double half_height_m) {
  const cylinder_state_detail::TiltFrame f =
      cylinder_state_detail::FrameOf(s.tilt_rad, s.azimuth_rad);
  // Contact point on the base, then the centre at -R e1 + h e3 from it.
  const double cp = std::cos(s.azimuth_rad), sp = std::sin(s.azimuth_rad);
  Vec3d c{radius_m * cp, radius_m * sp, 0.0};
  for (int i = 0; i < 3; ++i) c[i] += -radius_m * f.e1[i] + half_height_m * f.e3[i];
  return c;
}

inline Vec3d CylinderCentreVelocity(const CylinderState& s, double radius_m, double half_height_m) {
  const cylinder_state_detail::TiltFrame f =
      cylinder_state_detail::FrameOf(s.tilt_rad, s.azimuth_rad);
  const Vec3d w = CylinderAngularVelocity(s);
  Vec3d r;
  for (int i = 0; i < 3; ++i) r[i] = -radius_m * f.e1[i] + half_height_m * f.e3[i];
  return {w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]};
}

}  // namespace rockbench
