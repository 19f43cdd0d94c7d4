#include "reference/cylinder/cylinder_model.h"

#include <cmath>
#include <limits>

namespace rockbench::reference::cylinder {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The inertia about the contact point in the tilt frame, [[A, 0, B], [0, I_O, 0], [B, 0, C]]
// (docs/cylinder-3d.md section 2a), and Delta = A C - B^2.
struct ContactInertia {
  double a, b, c, pivot, delta;
};
ContactInertia ContactInertiaOf(const CylinderBody& body) {
  const double m = body.mass_kg, r = body.radius_m, h = body.half_height_m;
  const double it = body.inertia_transverse_kgm2(), ia = body.inertia_axial_kgm2();
  ContactInertia ic;
  ic.a = it + m * h * h;
  ic.b = m * r * h;
  ic.c = ia + m * r * r;
  ic.pivot = body.pivot_inertia_kgm2();
  // A C - B^2 written without the cancellation: I_t I_a + m (I_t R^2 + I_a h^2).
  ic.delta = it * ia + m * (it * r * r + ia * h * h);
  return ic;
}

}  // namespace

double CylinderBody::inertia_transverse_kgm2() const {
  return mass_kg * (3.0 * radius_m * radius_m + 4.0 * half_height_m * half_height_m) / 12.0;
}
double CylinderBody::inertia_axial_kgm2() const {
  return 0.5 * mass_kg * radius_m * radius_m;
}
double CylinderBody::pivot_inertia_kgm2() const {
  return inertia_transverse_kgm2() +
         mass_kg * (radius_m * radius_m + half_height_m * half_height_m);
}
double CylinderBody::critical_angle_rad() const {
  return std::atan2(radius_m, half_height_m);
}
double CylinderBody::time_scale_s() const {
  return std::sqrt(std::hypot(radius_m, half_height_m) / gravity_mps2);
}

CylinderBody MakeCylinderBody(double diameter_m, double height_m, double mass_kg,
                              double gravity_mps2) {
  return {0.5 * diameter_m, 0.5 * height_m, mass_kg, gravity_mps2};
}

double RimDynamics::friction_needed() const {
  if (!(force_n[2] > 0.0)) return std::numeric_limits<double>::infinity();
  return std::hypot(force_n[0], force_n[1]) / force_n[2];
}

RimDynamics Dynamics(const CylinderBody& body, const RimState& s, const BaseAccel& a) {
  const double m = body.mass_kg, r = body.radius_m, h = body.half_height_m, g = body.gravity_mps2;
  const double it = body.inertia_transverse_kgm2(), ia = body.inertia_axial_kgm2();
  const ContactInertia ic = ContactInertiaOf(body);
  const double st = std::sin(s.theta), ct = std::cos(s.theta);
  const double cp = s.cos_phi, sp = s.sin_phi;
  // The base's acceleration along the lean and across it.
  const double a_par = a[0] * cp + a[1] * sp;
  const double a_perp = -a[0] * sp + a[1] * cp;
  const double gz = g + a[2];
  const double td = s.theta_dot, pd = s.phi_dot;
  const double w3 = s.psi_dot + pd * ct;
  // The centre's height over the contact and its offset along the lean (< 0 restores).
  const double rho = r * st + h * ct;
  const double sigma = h * st - r * ct;
  // I_C omega_c' = b (docs/cylinder-3d.md section 2a).
  const double b1 = -ia * td * w3 + pd * td * (it * ct + m * h * rho) + m * h * a_perp;
  const double b2 = m * sigma * gz - m * rho * a_par + pd * pd * st * (it * ct + m * h * rho) -
                    pd * w3 * (ia * st + m * r * rho);
  const double b3 = m * r * (pd * td * rho + a_perp);
  RimDynamics d;
  d.theta_ddot = b2 / ic.pivot;
  const double w1_dot = (ic.c * b1 - ic.b * b3) / ic.delta;
  const double w3_dot = (ic.a * b3 - ic.b * b1) / ic.delta;
  // phi'' = -(w1' + phi' theta' cos theta) / sin theta; theta phi'' has the limit
  // -(w1' + phi' theta') at theta = 0 (theta / sin theta -> 1).
  const double numerator = w1_dot + pd * td * ct;
  d.theta_phi_ddot = -(st != 0.0 ? s.theta / st : 1.0) * numerator;
  d.axial_rate_dot = w3_dot;
  d.phi_ddot = st != 0.0 ? -numerator / st : 0.0;
  d.psi_ddot = w3_dot - d.phi_ddot * ct + pd * td * st;

  // The contact force F = m (a_G - G), a_G = omega_dot x r + omega x (Omega x r) in the frame.
  const Vec3 omega{-pd * st, td, w3};
  const Vec3 frame_rate{-pd * st, td, pd * ct};
  const Vec3 lever{-r, 0.0, h};
  const Vec3 turn = Cross(frame_rate, omega);
  const Vec3 omega_dot{w1_dot + turn[0], d.theta_ddot + turn[1], w3_dot + turn[2]};
  const Vec3 a1 = Cross(omega_dot, lever);
  const Vec3 a2 = Cross(omega, Cross(frame_rate, lever));
  const Vec3 e1{ct * cp, ct * sp, -st}, e2{-sp, cp, 0.0}, e3{st * cp, st * sp, ct};
  const Vec3 field{a[0], a[1], gz};
  for (int i = 0; i < 3; ++i) {
    const double accel =
        (a1[0] + a2[0]) * e1[i] + (a1[1] + a2[1]) * e2[i] + (a1[2] + a2[2]) * e3[i];
    d.force_n[i] = m * (accel + field[i]);
  }
  return d;
}

double Energy(const CylinderBody& body, const RimState& s) {
  const ContactInertia ic = ContactInertiaOf(body);
  const double st = std::sin(s.theta), ct = std::cos(s.theta);
  const double w1 = -s.phi_dot * st, w2 = s.theta_dot, w3 = s.psi_dot + s.phi_dot * ct;
  // Rolling: the kinetic energy is that of a rotation about the contact point.
  const double kinetic =
      0.5 * (ic.a * w1 * w1 + 2.0 * ic.b * w1 * w3 + ic.c * w3 * w3 + ic.pivot * w2 * w2);
  const double height = body.radius_m * st + body.half_height_m * ct - body.half_height_m;
  return kinetic + body.mass_kg * body.gravity_mps2 * height;
}

double PlanarRestitution(const CylinderBody& body) {
  const double m = body.mass_kg, r = body.radius_m;
  return 1.0 - 2.0 * m * r * r / body.pivot_inertia_kgm2();
}

Landing Land(const CylinderBody& body, const RimState& s) {
  const ContactInertia ic = ContactInertiaOf(body);
  const double m = body.mass_kg, r = body.radius_m, h = body.half_height_m;
  const double ia = body.inertia_axial_kgm2();
  const double st = std::sin(s.theta), ct = std::cos(s.theta);
  const double w1 = -s.phi_dot * st, w2 = s.theta_dot, w3 = s.psi_dot + s.phi_dot * ct;
  // About the new contact point: keep L'_2 and L'_3, stop w1 (docs/cylinder-3d.md section 5).
  const double w2_after = PlanarRestitution(body) * w2;
  const double w3_after = ((ia - m * r * r) * w3 - m * r * h * w1) / (ia + m * r * r);
  Landing l;
  // The new frame's e1 and e2 are the old ones reversed.
  l.theta_dot = -w2_after;
  l.axial_rate = w3_after;
  const double kinetic_before =
      0.5 * (ic.a * w1 * w1 + 2.0 * ic.b * w1 * w3 + ic.c * w3 * w3 + ic.pivot * w2 * w2);
  const double kinetic_after = 0.5 * (ic.pivot * w2_after * w2_after + ic.c * w3_after * w3_after);
  l.energy_lost_j = kinetic_before - kinetic_after;
  return l;
}

double OnsetMargin(const CylinderBody& body, const BaseAccel& a) {
  return body.half_height_m * std::hypot(a[0], a[1]) - body.radius_m * (body.gravity_mps2 + a[2]);
}

}  // namespace rockbench::reference::cylinder
