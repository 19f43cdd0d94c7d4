#pragma once
/// A solid circular cylinder rocking and rolling on one rim point of a translating rigid base,
/// without slip and without bouncing (docs/three-d.md; the derivation, twice, in
/// docs/cylinder-3d.md): its equations of motion (Newton-Euler about the contact point, in the
/// tilt frame), its contact force, the plastic landing on its face, and its onset from rest.
/// State: the ZYZ angles tilt theta, azimuth phi and spin psi (scene/cylinder_state.h) and
/// their rates. World axes: +x along [base.horizontal], +y along [base.transverse], +z up.
#include <array>

namespace rockbench::reference::cylinder {

/// The cylinder's mass properties and gravity.
struct CylinderBody {
  double radius_m = 0.0;       ///< R = D / 2
  double half_height_m = 0.0;  ///< h = H / 2
  double mass_kg = 0.0;
  double gravity_mps2 = 9.81;
  /// Central moments of inertia, kg m^2: I_t = m (3 R^2 + H^2) / 12 about a diameter through the
  /// centre, I_a = m R^2 / 2 about the axis (uniform density).
  double inertia_transverse_kgm2() const;
  double inertia_axial_kgm2() const;
  /// I_O = I_t + m (R^2 + h^2): about a rim point's tangent, the planar pivot inertia.
  double pivot_inertia_kgm2() const;
  /// alpha = atan(R / h) = atan(D / H): the critical angle of the planar limit.
  double critical_angle_rad() const;
  /// Characteristic time sqrt(R_c / g), R_c = sqrt(R^2 + h^2), s.
  double time_scale_s() const;
};

/// A body of diameter D, height H and mass m (uniform density) under gravity g.
CylinderBody MakeCylinderBody(double diameter_m, double height_m, double mass_kg,
                              double gravity_mps2);

/// The state on a rim point: angles (rad) and rates (rad/s). The azimuth enters only through its
/// cosine and sine, given apart (cos_phi, sin_phi), so that a planar motion keeps them exact
/// (sin phi = 0 stays 0 through every landing's half-turn).
struct RimState {
  double theta = 0.0, theta_dot = 0.0;
  double phi_dot = 0.0;
  double psi_dot = 0.0;
  double cos_phi = 1.0, sin_phi = 0.0;
};

/// Base acceleration, world components, m/s^2.
using BaseAccel = std::array<double, 3>;

/// The accelerations of the angles on a rim point, and the contact force.
struct RimDynamics {
  double theta_ddot = 0.0, phi_ddot = 0.0, psi_ddot = 0.0;  ///< rad/s^2
  /// The parts that stay finite at theta = 0, for the tilt vector's equations
  /// (reference/cylinder_run.cc): theta phi'' (its limit at theta = 0) and the rate of the
  /// axial rate w3 = psi' + phi' cos theta, rad/s^2.
  double theta_phi_ddot = 0.0, axial_rate_dot = 0.0;
  /// The contact force on the cylinder, world components, N: normal force_n = force[2],
  /// tangential (force[0], force[1]).
  std::array<double, 3> force_n{};
  /// The friction the rolling needs, |F_t| / N (inf when N <= 0).
  double friction_needed() const;
};

/// The equations of motion on the rim (docs/cylinder-3d.md section 2a): I_C omega_c' = b in the
/// tilt frame, solved in closed form. phi'' and psi'' divide by sin theta (0 at theta = 0);
/// theta_phi_ddot and axial_rate_dot do not: near upright the caller integrates the tilt vector
/// (theta cos phi, theta sin phi), whose equations are regular there.
RimDynamics Dynamics(const CylinderBody& body, const RimState& s, const BaseAccel& a);

/// Kinetic plus potential energy in the frame translating with the base, J (the potential of
/// gravity g alone, from the centre's height over the base with the cylinder upright at 0).
double Energy(const CylinderBody& body, const RimState& s);

/// The plastic landing on the face (docs/cylinder-3d.md section 5): the rim point at azimuth phi
/// lands its face at theta = 0 (or at the landing clearance); the cylinder goes on about the
/// diametrically opposite rim point (azimuth phi + pi) or rests. The angular momentum about the
/// new contact point is kept about the vertical and about the horizontal normal to the pivot's
/// diameter; the rate about the diameter is stopped by the face.
struct Landing {
  double theta_dot = 0.0;      ///< the tilt rate about the new rim point (>= 0 when it rocks on)
  double axial_rate = 0.0;     ///< w3 = psi' + phi' cos theta after the impact, rad/s
  double energy_lost_j = 0.0;  ///< kinetic energy before minus after (>= 0)
};
/// The landing of state `s` (its tilt rate < 0, about to land). The cylinder goes on from
/// upright, its tilt vector moving at theta_dot toward the new azimuth (at upright the tilt
/// vector's direction is its velocity's: no azimuth rate).
Landing Land(const CylinderBody& body, const RimState& s);

/// The planar limit's coefficient of restitution of the tilt rate, 1 - 2 m R^2 / I_O: what Land
/// gives with no azimuth or spin rate (negative for a squat cylinder: it lands flat).
double PlanarRestitution(const CylinderBody& body);

/// Onset from rest on the face (docs/cylinder-3d.md section 4.4): h |a_h| - R (g + a_z), m^2/s^2,
/// the tipping moment per unit mass of the horizontal field a_h about the rim point away from
/// it, less gravity's; > 0: the cylinder tips, its top leaning against the field (azimuth
/// atan2(-a_y, -a_x)).
double OnsetMargin(const CylinderBody& body, const BaseAccel& a);

}  // namespace rockbench::reference::cylinder
