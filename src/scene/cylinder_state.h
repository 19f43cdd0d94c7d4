#pragma once
/// What a cylinder's history columns mean (shape "cylinder", docs/three-d.md): its orientation
/// as ZYZ Euler angles Q = Rz(azimuth) Ry(tilt) Rz(spin) (world axes: +x along
/// [base.horizontal], +y along [base.transverse], +z up), the rates of those angles, and the
/// pose of a cylinder standing on the rim point on the side it leans toward. One conversion for
/// the reference, every engine and the renders.
#include <array>

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

}  // namespace rockbench
