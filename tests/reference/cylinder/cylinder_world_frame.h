#pragma once
// An independent second formulation of a rigid solid circular cylinder rolling on one rim point
// (no slip, no bouncing) on a translating rigid base, written for the tests only as an oracle for
// reference/cylinder/ (it shares no code and no equations with it). Conventions are those of
// docs/cylinder-3d.md sections 0, 1 and 3 (axes, ZYZ angles, the lowest rim point as the contact);
// the equations of motion are derived here afresh, in the world frame, with the orientation as a
// unit quaternion and no Euler-angle equations of motion.
//
// Derivation (all vectors in world components, in the frame translating with the base, where the
// effective gravity per unit mass is G = (-a_x, -a_y, -(g + a_z))):
// - k = Q e_z is the body axis. u = -z + (z . k) k is the downward slope direction in the bottom
//   face, |u| = s = sin(tilt); e1 = u / s. The contact point (lowest rim point) is
//   P = x_G - h k + R e1; r = x_G - P = h k - R e1.
// - No slip: the body's material point at P is at rest, so v_G = omega x r for every state. Its
//   time derivative along the motion: a_G = alpha x r + omega x r_dot, where r moves with the
//   geometric point (not with the body): r_dot = h k_dot - R e1_dot, k_dot = omega x k,
//   u_dot = (z . k_dot) k + (z . k) k_dot, e1_dot = (u_dot - e1 (e1 . u_dot)) / s.
// - Newton: F = m (a_G - G), the true contact force. Euler about the centre in world components:
//   I_w alpha + omega x (I_w omega) = (P - x_G) x F = -r x F, I_w = Q diag(I_t, I_t, I_a) Q^T.
//   Substituting F, -m r x (alpha x r) = -m (|r|^2 1 - r r^T) alpha, so alpha solves the
//   symmetric positive definite 3x3 system
//     [I_w + m (|r|^2 1 - r r^T)] alpha = -omega x (I_w omega) - m r x (omega x r_dot - G)
//   (the matrix is the inertia about the contact point).
// - Kinematics: q_dot = 1/2 (0, omega) (x) q (Hamilton product, omega in world components).
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <numbers>

namespace rockbench::reference::test {

/// A rigid circular cylinder: radius R (m), half-height h (m), mass m (kg), central inertia
/// about a transverse axis I_t and about its own axis I_a (kg m^2).
struct CylinderBody {
  double radius_m = 0.0;
  double half_height_m = 0.0;
  double mass_kg = 0.0;
  double inertia_transverse_kgm2 = 0.0;
  double inertia_axial_kgm2 = 0.0;
};

/// A homogeneous solid cylinder of diameter D (m), height H (m) and density rho (kg/m^3):
/// m = rho pi R^2 H, I_a = m R^2 / 2, I_t = m (3 R^2 + H^2) / 12.
inline CylinderBody SolidCylinder(double diameter_m, double height_m, double density_kgpm3) {
  CylinderBody b;
  b.radius_m = 0.5 * diameter_m;
  b.half_height_m = 0.5 * height_m;
  b.mass_kg = density_kgpm3 * std::numbers::pi * b.radius_m * b.radius_m * height_m;
  b.inertia_axial_kgm2 = 0.5 * b.mass_kg * b.radius_m * b.radius_m;
  b.inertia_transverse_kgm2 =
      b.mass_kg * (3.0 * b.radius_m * b.radius_m + height_m * height_m) / 12.0;
  return b;
}

/// The state y = (q_w, q_x, q_y, q_z, w_x, w_y, w_z): the orientation quaternion (body to world,
/// unit; Derivative normalises a copy to build the rotation) and the angular velocity in world
/// components (rad/s). The centre's velocity follows from the rolling constraint.
using CylinderState = std::array<double, 7>;

/// The orientation quaternion of a state, normalised.
inline Eigen::Quaterniond OrientationOf(const CylinderState& y) {
  return Eigen::Quaterniond(y[0], y[1], y[2], y[3]).normalized();
}

/// The angular velocity of a state, world components (rad/s).
inline Eigen::Vector3d AngularVelocityOf(const CylinderState& y) {
  return {y[4], y[5], y[6]};
}

/// The geometry of the rim contact in a state, world components.
struct RimContact {
  Eigen::Matrix3d rotation;  ///< Q, body to world
  Eigen::Vector3d axis;      ///< k = Q e_z (unitless)
  Eigen::Vector3d e1;        ///< the in-face direction pointing down-slope (unitless)
  double sin_tilt = 0.0;     ///< s = |u| = sin(theta) (unitless)
  Eigen::Vector3d r_m;       ///< r = x_G - P = h k - R e1 (m)
};

/// The contact geometry of a state (valid for 0 < theta < pi, where e1 is defined).
inline RimContact ContactOf(const CylinderBody& body, const CylinderState& y) {
  RimContact c;
  c.rotation = OrientationOf(y).toRotationMatrix();
  c.axis = c.rotation.col(2);
  const Eigen::Vector3d& k = c.axis;
  // u = -z + (z . k) k, written with 1 - k_z^2 = k_x^2 + k_y^2 (|k| = 1) so that its vertical
  // component keeps its digits near upright (no 1 - cos^2 cancellation).
  const double horizontal2 = k.x() * k.x() + k.y() * k.y();
  const Eigen::Vector3d u(k.z() * k.x(), k.z() * k.y(), -horizontal2);
  c.sin_tilt = u.norm();
  c.e1 = u / c.sin_tilt;
  c.r_m = body.half_height_m * k - body.radius_m * c.e1;
  return c;
}

/// The centre's velocity relative to the base from the rolling constraint, v_G = omega x r (m/s).
inline Eigen::Vector3d CentreVelocity(const CylinderBody& body, const CylinderState& y) {
  return AngularVelocityOf(y).cross(ContactOf(body, y).r_m);
}

/// The centre's height above the base, z_G - z_P = r_z = R sin(theta) + h cos(theta) (m).
inline double CentreHeight(const CylinderBody& body, const CylinderState& y) {
  return ContactOf(body, y).r_m.z();
}

/// The state derivative and the contact force.
struct CylinderDerivative {
  CylinderState dstate{};                     ///< (q_dot (1/s), alpha (rad/s^2))
  Eigen::Vector3d contact_force_N;            ///< F, the base's force on the body, world (N)
  Eigen::Vector3d centre_acceleration_mps2;   ///< a_G relative to the base, world (m/s^2)
  Eigen::Vector3d angular_acceleration_rps2;  ///< alpha, world (rad/s^2)
  /// The normal force N = F_z (N); N < 0 means the rim would lift off.
  double normal_N() const { return contact_force_N.z(); }
};

/// The state derivative while rolling on the rim, with the base accelerating by
/// accel_base_mps2 = (a_x, a_y, a_z) (m/s^2) and gravity g_mps2 > 0 along -z (m/s^2).
inline CylinderDerivative Derivative(const CylinderBody& body, const CylinderState& y,
                                     const std::array<double, 3>& accel_base_mps2, double g_mps2) {
  const RimContact c = ContactOf(body, y);
  const Eigen::Vector3d omega = AngularVelocityOf(y);
  const Eigen::Vector3d& k = c.axis;
  const Eigen::Vector3d& r = c.r_m;
  const double m = body.mass_kg;
  // The rate of r as the geometric contact point moves around the rim.
  const Eigen::Vector3d k_dot = omega.cross(k);
  const Eigen::Vector3d u_dot = k_dot.z() * k + k.z() * k_dot;
  const Eigen::Vector3d e1_dot = (u_dot - c.e1 * c.e1.dot(u_dot)) / c.sin_tilt;
  const Eigen::Vector3d r_dot = body.half_height_m * k_dot - body.radius_m * e1_dot;
  // Inertia in world components, and the effective gravity in the base's frame.
  const Eigen::Matrix3d inertia_world =
      c.rotation *
      Eigen::Vector3d(body.inertia_transverse_kgm2, body.inertia_transverse_kgm2,
                      body.inertia_axial_kgm2)
          .asDiagonal() *
      c.rotation.transpose();
  const Eigen::Vector3d gravity_eff(-accel_base_mps2[0], -accel_base_mps2[1],
                                    -(g_mps2 + accel_base_mps2[2]));
  // Euler about the centre with F = m (alpha x r + omega x r_dot - G): linear in alpha.
  const Eigen::Matrix3d a_matrix =
      inertia_world + m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  const Eigen::Vector3d rhs =
      -omega.cross(inertia_world * omega) - m * r.cross(omega.cross(r_dot) - gravity_eff);
  const Eigen::Vector3d alpha = a_matrix.ldlt().solve(rhs);
  CylinderDerivative d;
  d.angular_acceleration_rps2 = alpha;
  d.centre_acceleration_mps2 = alpha.cross(r) + omega.cross(r_dot);
  d.contact_force_N = m * (d.centre_acceleration_mps2 - gravity_eff);
  // q_dot = 1/2 (0, omega) (x) q = 1/2 (-omega . v, w omega + omega x v).
  const double qw = y[0];
  const Eigen::Vector3d qv(y[1], y[2], y[3]);
  const Eigen::Vector3d qv_dot = 0.5 * (qw * omega + omega.cross(qv));
  d.dstate = {
      -0.5 * omega.dot(qv), qv_dot.x(), qv_dot.y(), qv_dot.z(), alpha.x(), alpha.y(), alpha.z()};
  return d;
}

/// The energy on a fixed base (J): 1/2 m |v_G|^2 + 1/2 omega . I_w omega + m g z_G, with
/// z_G = R sin(theta) + h cos(theta) the centre's height (m) and g_mps2 (m/s^2).
inline double Energy(const CylinderBody& body, const CylinderState& y, double g_mps2) {
  const RimContact c = ContactOf(body, y);
  const Eigen::Vector3d omega = AngularVelocityOf(y);
  const Eigen::Vector3d omega_body = c.rotation.transpose() * omega;
  const Eigen::Vector3d v = omega.cross(c.r_m);
  const double rotational =
      0.5 * (body.inertia_transverse_kgm2 *
                 (omega_body.x() * omega_body.x() + omega_body.y() * omega_body.y()) +
             body.inertia_axial_kgm2 * omega_body.z() * omega_body.z());
  return 0.5 * body.mass_kg * v.squaredNorm() + rotational + body.mass_kg * g_mps2 * c.r_m.z();
}

/// ZYZ Euler angles Q = Rz(phi) Ry(theta) Rz(psi) and their rates: tilt theta (rad), azimuth of
/// the lean phi (rad, from +x toward +y), spin psi (rad), and their rates (rad/s).
struct TiltAzimuthSpin {
  double theta_rad = 0.0, phi_rad = 0.0, psi_rad = 0.0;
  double theta_dot_radps = 0.0, phi_dot_radps = 0.0, psi_dot_radps = 0.0;
  /// The tilt's components theta cos(phi), theta sin(phi) (rad).
  double tilt_x_rad() const { return theta_rad * std::cos(phi_rad); }
  double tilt_y_rad() const { return theta_rad * std::sin(phi_rad); }
};

/// The state of the ZYZ angles (rad) and rates (rad/s). With k = Q e_z and
/// e2 = Rz(phi) e_y = (-sin phi, cos phi, 0), the angular velocity in world components is
/// omega = phi' e_z + theta' e2 + psi' k (each rate about its own axis, composed outward in).
inline CylinderState FromTiltAzimuthSpin(double theta_rad, double phi_rad, double psi_rad,
                                         double theta_dot_radps, double phi_dot_radps,
                                         double psi_dot_radps) {
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::AngleAxisd(phi_rad, Eigen::Vector3d::UnitZ())) *
      Eigen::Quaterniond(Eigen::AngleAxisd(theta_rad, Eigen::Vector3d::UnitY())) *
      Eigen::Quaterniond(Eigen::AngleAxisd(psi_rad, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d k = q.toRotationMatrix().col(2);
  const Eigen::Vector3d e2(-std::sin(phi_rad), std::cos(phi_rad), 0.0);
  const Eigen::Vector3d omega =
      phi_dot_radps * Eigen::Vector3d::UnitZ() + theta_dot_radps * e2 + psi_dot_radps * k;
  return {q.w(), q.x(), q.y(), q.z(), omega.x(), omega.y(), omega.z()};
}

/// The ZYZ angles (rad) and rates (rad/s) of a state, valid for 0 < theta < pi; phi and psi in
/// (-pi, pi]. With Q = Rz(phi) Ry(theta) Rz(psi), the third column of Q is
/// (sin th cos phi, sin th sin phi, cos th) and its third row (-sin th cos psi, sin th sin psi,
/// cos th). The rates invert omega = phi' e_z + theta' e2 + psi' k with
/// e1 = (cos th cos phi, cos th sin phi, -sin th): e2 is normal to e_z and k, so theta' = omega .
/// e2; e1 is normal to e2 and k with e1 . e_z = -sin th, so phi' = -omega . e1 / sin th; and omega
/// . k = phi' cos th + psi'.
inline TiltAzimuthSpin ToTiltAzimuthSpin(const CylinderState& y) {
  const Eigen::Matrix3d q = OrientationOf(y).toRotationMatrix();
  TiltAzimuthSpin a;
  a.theta_rad = std::atan2(std::hypot(q(0, 2), q(1, 2)), q(2, 2));
  a.phi_rad = std::atan2(q(1, 2), q(0, 2));
  a.psi_rad = std::atan2(q(2, 1), -q(2, 0));
  const double st = std::sin(a.theta_rad), ct = std::cos(a.theta_rad);
  const double sp = std::sin(a.phi_rad), cp = std::cos(a.phi_rad);
  const Eigen::Vector3d e1(ct * cp, ct * sp, -st), e2(-sp, cp, 0.0);
  const Eigen::Vector3d omega = AngularVelocityOf(y);
  a.theta_dot_radps = omega.dot(e2);
  a.phi_dot_radps = -omega.dot(e1) / st;
  a.psi_dot_radps = omega.dot(q.col(2)) - a.phi_dot_radps * ct;
  return a;
}

}  // namespace rockbench::reference::test
