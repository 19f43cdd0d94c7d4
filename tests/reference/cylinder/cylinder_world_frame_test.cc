// The world-frame, quaternion formulation of a cylinder rolling on its rim
// (cylinder_world_frame.h) checked on its own: the angle conversions round-trip, the centre's
// acceleration is the time derivative of the rolling constraint's velocity, energy is conserved
// on a fixed base, the closed forms at rest and in the planar limit hold, and rotating the base
// motion about the vertical rotates the motion. Integration: Dormand-Prince 8(5,3) steps from
// reference/integration/integrator.h with a step-size controller written here; the quaternion is
// never renormalised (Derivative normalises a copy to build the rotation).
#include "reference/cylinder/cylinder_world_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "reference/integration/integrator.h"

namespace rockbench::reference::test {
namespace {

constexpr double kG = 9.81;  // m/s^2
constexpr double kPi = std::numbers::pi;

// The body of docs/cylinder-3d.md's numerical demonstration: D = 0.5 m, H = 1.5 m, granite-like.
CylinderBody Body() {
  return SolidCylinder(0.5, 1.5, 2500.0);
}

// Corner-to-centre distance R_c (m), alpha = atan(R / h) (rad), pivot inertia I_O (kg m^2).
struct Planar {
  double rc_m, alpha_rad, io_kgm2;
};
Planar PlanarOf(const CylinderBody& b) {
  const double rc = std::hypot(b.radius_m, b.half_height_m);
  return {rc, std::atan2(b.radius_m, b.half_height_m),
          b.inertia_transverse_kgm2 + b.mass_kg * rc * rc};
}

// The difference of two angles wrapped to (-pi, pi] (rad).
double AngleDiff(double a, double b) {
  return std::remainder(a - b, 2.0 * kPi);
}

// A solution: the accepted steps' ends (t, y) and their dense outputs.
template <size_t D>
struct Trajectory {
  std::vector<double> t;
  std::vector<VecN<D>> y;
  std::vector<DenseStepN<D>> dense;
  /// The state at time t in [0, t.back()] (the dense output of the step holding t).
  VecN<D> At(double time) const {
    const auto it = std::lower_bound(t.begin() + 1, t.end(), time);
    return dense[std::min<size_t>(it - t.begin(), dense.size()) - 1].At(time);
  }
};

// Integrates y' = rhs(t, y) from t = 0 to t_end with adaptive DOP853 steps (error <= 1 per step
// at rtol, atol).
template <size_t D, class Rhs>
Trajectory<D> Integrate(const Rhs& rhs, VecN<D> y, double t_end, double rtol, double atol) {
  Trajectory<D> out;
  double t = 0.0, h = 1e-3;
  VecN<D> f = rhs(t, y);
  out.t.push_back(t);
  out.y.push_back(y);
  while (t < t_end) {
    h = std::min(h, t_end - t);
    const StepResultN<D> s = Dop853Step(rhs, t, y, f, h, rtol, atol);
    // The usual controller (Hairer et al. II.4): exponent 1/8, safety 0.9, factor in [1/3, 6].
    const double factor =
        std::clamp(0.9 * std::pow(std::max(s.err, 1e-300), -1.0 / 8.0), 1.0 / 3.0, 6.0);
    if (s.err <= 1.0) {
      t = (h == t_end - t) ? t_end : t + h;
      y = s.y1;
      f = s.f1;
      out.t.push_back(t);
      out.y.push_back(y);
      out.dense.push_back(s.dense);
    }
    h *= factor;
  }
  return out;
}

CylinderState StateOf(const VecN<13>& y) {
  CylinderState s;
  std::copy_n(y.begin(), 7, s.begin());
  return s;
}

// 1. FromTiltAzimuthSpin and ToTiltAzimuthSpin invert each other.
TEST(CylinderWorldFrame, AnglesAndRatesRoundTrip) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> theta(0.01, 1.5), angle(-3.1, 3.1), rate(-6.0, 6.0);
  double worst_angle = 0.0, worst_rate = 0.0;
  for (int i = 0; i < 10000; ++i) {
    const double th = theta(rng), ph = angle(rng), ps = angle(rng);
    const double thd = rate(rng), phd = rate(rng), psd = rate(rng);
    const CylinderState y = FromTiltAzimuthSpin(th, ph, ps, thd, phd, psd);
    const TiltAzimuthSpin a = ToTiltAzimuthSpin(y);
    // The angles pass through a quaternion, a rotation matrix and atan2: a few ulps of pi.
    const double e_angle = std::max({std::abs(a.theta_rad - th), std::abs(AngleDiff(a.phi_rad, ph)),
                                     std::abs(AngleDiff(a.psi_rad, ps))});
    EXPECT_LT(e_angle, 1e-14) << th << " " << ph << " " << ps;
    // phi' = -omega . e1 / sin theta: omega . e1 carries rounding of a few ulps of |omega| <= 18
    // rad/s (4e-15), which the division by sin theta >= 0.01 magnifies; so the bound on a rate's
    // error is 1e-14 (|omega| / 6 rad/s) / sin theta.
    const double scale = std::max(1.0, std::hypot(thd, phd, psd) / 6.0) / std::sin(th);
    const double e_rate =
        std::max({std::abs(a.theta_dot_radps - thd), std::abs(a.phi_dot_radps - phd),
                  std::abs(a.psi_dot_radps - psd)}) /
        scale;
    EXPECT_LT(e_rate, 1e-14) << th << " " << thd << " " << phd << " " << psd;
    worst_angle = std::max(worst_angle, e_angle);
    worst_rate = std::max(worst_rate, e_rate);
    // The tilt components.
    EXPECT_NEAR(a.tilt_x_rad(), th * std::cos(ph), 1e-14);
    EXPECT_NEAR(a.tilt_y_rad(), th * std::sin(ph), 1e-14);
  }
  std::printf("round trip: angles %.2e rad, rates %.2e (scaled)\n", worst_angle, worst_rate);
}

// The contact point is the lowest rim point (the rim point of least height), and the rolling
// constraint's velocity leaves the material contact point at rest.
TEST(CylinderWorldFrame, ContactIsTheLowestRimPointAndAtRest) {
  const CylinderBody b = Body();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> theta(0.01, 1.5), angle(-3.1, 3.1), rate(-6.0, 6.0);
  for (int i = 0; i < 200; ++i) {
    const CylinderState y =
        FromTiltAzimuthSpin(theta(rng), angle(rng), angle(rng), rate(rng), rate(rng), rate(rng));
    const RimContact c = ContactOf(b, y);
    // P - x_G = -r; every rim point of the bottom face is Q (R cos u, R sin u, -h).
    const double contact_z = -c.r_m.z();
    double lowest = 1e300;
    for (int j = 0; j < 3600; ++j) {
      const double u = 2.0 * kPi * j / 3600;
      const Eigen::Vector3d p =
          c.rotation *
          Eigen::Vector3d(b.radius_m * std::cos(u), b.radius_m * std::sin(u), -b.half_height_m);
      lowest = std::min(lowest, p.z());
      // The top rim is never lower (0 < theta < pi/2).
      EXPECT_GE(p.z() + 2.0 * b.half_height_m * c.axis.z(), contact_z - 1e-15);
    }
    // The grid's step is 2 pi / 3600 of the rim: a rim point within du of the lowest is higher
    // by at most R sin(theta) du^2 / 2 <= 0.25 * 1.5e-6 m; and never lower than the contact.
    EXPECT_LE(contact_z, lowest + 1e-15);
    EXPECT_GT(contact_z, lowest - 1e-6);
    // The material contact point's velocity v_G + omega x (P - x_G) vanishes.
    const Eigen::Vector3d omega = AngularVelocityOf(y);
    const Eigen::Vector3d v_p = CentreVelocity(b, y) + omega.cross(-c.r_m);
    EXPECT_LT(v_p.norm(), 1e-14);
  }
}

// 2a. The centre's acceleration Derivative returns is the time derivative of v_G(y) = omega x r
// along the motion: a central difference of v_G along y' (step 1e-5 s).
TEST(CylinderWorldFrame, CentreAccelerationDifferentiatesTheConstraintVelocity) {
  const CylinderBody b = Body();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> theta(0.05, 1.4), angle(-3.1, 3.1), rate(-4.0, 4.0),
      accel(-3.0, 3.0);
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    const CylinderState y =
        FromTiltAzimuthSpin(theta(rng), angle(rng), angle(rng), rate(rng), rate(rng), rate(rng));
    const std::array<double, 3> a_base = {accel(rng), accel(rng), accel(rng)};
    const CylinderDerivative d = Derivative(b, y, a_base, kG);
    constexpr double kDt = 1e-5;
    CylinderState yp, ym;
    for (int j = 0; j < 7; ++j) {
      yp[j] = y[j] + kDt * d.dstate[j];
      ym[j] = y[j] - kDt * d.dstate[j];
    }
    const Eigen::Vector3d a_fd = (CentreVelocity(b, yp) - CentreVelocity(b, ym)) / (2.0 * kDt);
    // The central difference errs by dt^2 / 6 times the third derivative (~1e3 m/s^3 here at
    // most: rates of 4 rad/s over lengths of 1 m, cubed) ~ 2e-8, plus rounding of 1e-16 * 5 m/s
    // / 1e-5 s = 5e-11: 1e-7 m/s^2 with the scale of the accelerations (>= 1 m/s^2).
    const double scale = std::max(1.0, d.centre_acceleration_mps2.norm());
    const double e = (a_fd - d.centre_acceleration_mps2).norm() / scale;
    EXPECT_LT(e, 1e-7);
    worst = std::max(worst, e);
    // F = m (a_G - G), the definition of the contact force.
    const Eigen::Vector3d g_eff(-a_base[0], -a_base[1], -(kG + a_base[2]));
    EXPECT_LT((d.contact_force_N - b.mass_kg * (d.centre_acceleration_mps2 - g_eff)).norm(),
              1e-12 * b.mass_kg * scale);
    // Euler about the centre with F as returned (the solve used the contact point's inertia).
    const RimContact c = ContactOf(b, y);
    const Eigen::Matrix3d iw =
        c.rotation *
        Eigen::Vector3d(b.inertia_transverse_kgm2, b.inertia_transverse_kgm2, b.inertia_axial_kgm2)
            .asDiagonal() *
        c.rotation.transpose();
    const Eigen::Vector3d omega = AngularVelocityOf(y);
    const Eigen::Vector3d lhs = iw * d.angular_acceleration_rps2 + omega.cross(iw * omega);
    const Eigen::Vector3d rhs = (-c.r_m).cross(d.contact_force_N);
    // Torques of ~1e4 N m; the 3x3 solve leaves residuals of a few ulps of them.
    EXPECT_LT((lhs - rhs).norm(), 1e-11 * std::max(1.0, rhs.norm()));
  }
  std::printf("a_G vs central difference of v_G: worst relative %.2e\n", worst);
}

// 2b. Free rolling on a fixed base: energy is conserved, the centre's height integrated from the
// constraint's vertical velocity stays the rim geometry's R sin(theta) + h cos(theta), and the
// centre's velocity integrated from F / m + G stays the constraint's omega x r.
TEST(CylinderWorldFrame, FreeRollingConservesEnergyAndKeepsTheConstraint) {
  const CylinderBody b = Body();
  const std::array<double, 3> still = {0.0, 0.0, 0.0};
  // y = (q, omega, x_G, y_G, z_G from v_G = omega x r, v from F / m + G).
  auto rhs = [&](double, const VecN<13>& y) {
    const CylinderState s = StateOf(y);
    const CylinderDerivative d = Derivative(b, s, still, kG);
    const Eigen::Vector3d v = CentreVelocity(b, s);
    VecN<13> f;
    std::copy_n(d.dstate.begin(), 7, f.begin());
    for (int j = 0; j < 3; ++j) {
      f[7 + j] = v[j];
      f[10 + j] = d.centre_acceleration_mps2[j];
    }
    return f;
  };
  for (int phi_dot = 1; phi_dot <= 6; ++phi_dot) {
    const CylinderState s0 = FromTiltAzimuthSpin(0.1, 0.0, 0.0, 0.0, phi_dot, 0.0);
    VecN<13> y0{};
    std::copy_n(s0.begin(), 7, y0.begin());
    const Eigen::Vector3d v0 = CentreVelocity(b, s0);
    y0[9] = CentreHeight(b, s0);
    for (int j = 0; j < 3; ++j) y0[10 + j] = v0[j];
    const double e0 = Energy(b, s0, kG);
    double drift = 0.0, kinetic_max = 0.0, height_err = 0.0, velocity_err = 0.0, norm_err = 0.0;
    double theta_min = 1e9, theta_max = 0.0, n_min = 1e300, n_max = -1e300, friction = 0.0;
    const Trajectory<13> run = Integrate<13>(rhs, y0, 4.0, 1e-13, 1e-13);
    for (const VecN<13>& y : run.y) {
      const CylinderState s = StateOf(y);
      const double e = Energy(b, s, kG);
      drift = std::max(drift, std::abs(e - e0) / e0);
      kinetic_max = std::max(kinetic_max, e - b.mass_kg * kG * CentreHeight(b, s));
      height_err = std::max(height_err, std::abs(y[9] - CentreHeight(b, s)));
      const Eigen::Vector3d v = CentreVelocity(b, s);
      velocity_err = std::max(velocity_err, (Eigen::Vector3d(y[10], y[11], y[12]) - v).norm());
      norm_err = std::max(
          norm_err,
          std::abs(std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3]) - 1.0));
      const double th = ToTiltAzimuthSpin(s).theta_rad;
      theta_min = std::min(theta_min, th);
      theta_max = std::max(theta_max, th);
      const CylinderDerivative d = Derivative(b, s, still, kG);
      const double n = d.normal_N() / (b.mass_kg * kG);
      friction = std::max(friction,
                          std::hypot(d.contact_force_N.x(), d.contact_force_N.y()) / d.normal_N());
      n_min = std::min(n_min, n);
      n_max = std::max(n_max, n);
    }
    std::printf(
        "phi0' = %d rad/s: theta in [%.4f, %.4f], N/mg in [%.3f, %.3f], |F_t|/N <= %.3f; energy "
        "drift %.2e of E0 "
        "(%.2e of max kinetic), z_G %.2e m, v_G %.2e m/s, |q| - 1 %.2e\n",
        phi_dot, theta_min, theta_max, n_min, n_max, friction, drift, drift * e0 / kinetic_max,
        height_err, velocity_err, norm_err);
    // The rim model holds throughout: the tilt stays away from upright and the rim pressed.
    EXPECT_GT(theta_min, 0.01);
    EXPECT_GT(n_min, 0.0);
    // The steps keep a local error of 1e-13 relative; over a few hundred steps that bounds the
    // drift by 1e-10 of E0 (the brief's bound; measured <= 9e-14) and, tighter, by 1e-11 of the
    // largest kinetic energy (the part that moves; measured <= 6e-13).
    EXPECT_LT(drift, 1e-10);
    EXPECT_LT(drift * e0 / kinetic_max, 1e-11);
    // The integrated height and velocity and |q| carry the same per-step error: lengths of 1 m,
    // speeds of a few m/s: 1e-11 over 4 s (measured <= 4e-15 m, 3e-12 m/s, 2e-15).
    EXPECT_LT(height_err, 1e-11);
    EXPECT_LT(velocity_err, 1e-11);
    EXPECT_LT(norm_err, 1e-11);
  }
}

// 3. At rest on the rim at tilt theta (any azimuth and spin, fixed base) the body starts to
// roll as the planar rocking block about its corner: theta'' = m g R_c sin(theta - alpha) / I_O
// (gravity's torque about the contact over the inertia about it). The centre is at
// z = R_c cos(theta - alpha) and, along the lean, R_c sin(theta - alpha) from the contact, so
// F_z = m (g + z'') = m g (1 - m R_c^2 sin^2(theta - alpha) / I_O) and the force along the lean
// F_par = m x'' = m R_c cos(theta - alpha) theta''. At theta = alpha the body balances: F = m g e_z
// and alpha = 0. Near upright (theta -> 0+) N -> m g (1 - m R^2 / I_O), not m g: the rim model's
// limit differs from resting on the face.
TEST(CylinderWorldFrame, AtRestOnTheRimMatchesThePlanarCornerClosedForm) {
  const CylinderBody b = Body();
  const Planar p = PlanarOf(b);
  const double m = b.mass_kg, mg = m * kG;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> theta(1e-9, 1.5), angle(-3.1, 3.1);
  auto check = [&](double th, double ph, double ps, double tol) {
    const CylinderState y = FromTiltAzimuthSpin(th, ph, ps, 0.0, 0.0, 0.0);
    const CylinderDerivative d = Derivative(b, y, {0.0, 0.0, 0.0}, kG);
    const double sn = std::sin(th - p.alpha_rad), cs = std::cos(th - p.alpha_rad);
    const double theta_dd = m * kG * p.rc_m * sn / p.io_kgm2;
    const Eigen::Vector3d lean(std::cos(ph), std::sin(ph), 0.0), e2(-std::sin(ph), std::cos(ph), 0);
    EXPECT_NEAR(d.normal_N(), mg * (1.0 - m * p.rc_m * p.rc_m * sn * sn / p.io_kgm2), tol * mg);
    EXPECT_NEAR(d.contact_force_N.dot(lean), m * p.rc_m * cs * theta_dd, tol * mg);
    EXPECT_NEAR(d.contact_force_N.dot(e2), 0.0, tol * mg);
    // The angular acceleration is theta'' about e2 (the tilt axis), nothing else.
    EXPECT_LT((d.angular_acceleration_rps2 - theta_dd * e2).norm(), tol * 30.0);
    return d;
  };
  // Roundoff: the solve and the products are accurate to a few ulps of m g and of the
  // accelerations (~ 10 rad/s^2): 1e-13 relative is a few hundred ulps.
  for (int i = 0; i < 1000; ++i) check(theta(rng), angle(rng), angle(rng), 1e-13);
  // Near upright.
  const CylinderDerivative up = check(1e-10, 0.4, -1.2, 1e-13);
  const double io = p.io_kgm2, r2 = b.radius_m * b.radius_m;
  EXPECT_NEAR(up.normal_N(), mg * (1.0 - m * r2 / io), 1e-9 * mg);
  std::printf("at rest near upright: N / m g = %.15f (1 - m R^2 / I_O = %.15f)\n",
              up.normal_N() / mg, 1.0 - m * r2 / io);
  // Balanced on the rim.
  const CylinderDerivative bal = check(p.alpha_rad, 1.0, 2.0, 1e-13);
  EXPECT_NEAR(bal.normal_N(), mg, 1e-13 * mg);
  EXPECT_LT(bal.angular_acceleration_rps2.norm(), 1e-13);
}

// 4a. Planar limit, pointwise: phi = 0, phi' = psi' = 0, base accelerating in x and z. theta''
// is the planar rocking block's m R_c [(g + a_z) sin(theta - alpha) - a_x cos(theta - alpha)] / I_O
// and the motion has no out-of-plane acceleration; the contact force is m times the centre's
// acceleration about the fixed corner (x = R_c sin(theta - alpha), z = R_c cos(theta - alpha))
// minus the effective gravity.
TEST(CylinderWorldFrame, PlanarLimitMatchesTheRockingBlockPointwise) {
  const CylinderBody b = Body();
  const Planar p = PlanarOf(b);
  const double m = b.mass_kg;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> theta(0.01, 1.5), spin(-3.1, 3.1), rate(-3.0, 3.0),
      accel(-5.0, 5.0);
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double th = theta(rng), thd = rate(rng), ax = accel(rng), az = accel(rng);
    const CylinderState y = FromTiltAzimuthSpin(th, 0.0, spin(rng), thd, 0.0, 0.0);
    const CylinderDerivative d = Derivative(b, y, {ax, 0.0, az}, kG);
    const double sn = std::sin(th - p.alpha_rad), cs = std::cos(th - p.alpha_rad);
    const double theta_dd = m * p.rc_m * ((kG + az) * sn - ax * cs) / p.io_kgm2;
    // With phi' = 0, e2 = e_y is fixed, so theta'' = alpha . e_y.
    const Eigen::Vector3d& alpha = d.angular_acceleration_rps2;
    // 1e-12 relative to the scale of the accelerations (>= 1 rad/s^2): the solve's rounding is a
    // few ulps of the largest term, and theta'' passes through zero.
    const double scale = std::max(1.0, std::abs(theta_dd));
    const double e = std::abs(alpha.y() - theta_dd) / scale;
    EXPECT_LT(e, 1e-12) << th << " " << thd << " " << ax << " " << az;
    worst = std::max(worst, e);
    EXPECT_LT(std::abs(alpha.x()) + std::abs(alpha.z()), 1e-12 * scale);
    const double xdd = p.rc_m * (cs * theta_dd - sn * thd * thd);
    const double zdd = p.rc_m * (-sn * theta_dd - cs * thd * thd);
    const double fscale = m * (kG + 10.0);
    EXPECT_NEAR(d.contact_force_N.x(), m * (xdd + ax), 1e-12 * fscale);
    EXPECT_NEAR(d.contact_force_N.y(), 0.0, 1e-12 * fscale);
    EXPECT_NEAR(d.contact_force_N.z(), m * (zdd + kG + az), 1e-12 * fscale);
  }
  std::printf("planar theta'': worst relative error %.2e\n", worst);
}

// The base motion of the trajectory tests (m/s^2): a few smooth pulses.
std::array<double, 3> BaseAccel(double t, double beta_rad) {
  const double ax = 0.8 * std::sin(2.1 * t) + 0.3 * std::cos(5.3 * t);
  const double ay = 0.5 * std::sin(3.7 * t + 0.4);
  const double az = 0.4 * std::sin(4.4 * t);
  const double c = std::cos(beta_rad), s = std::sin(beta_rad);
  return {c * ax - s * ay, s * ax + c * ay, az};
}

// 4b. Planar limit along a trajectory: driven by a_x(t), a_z(t) from phi = 0 the motion stays in
// the xz plane and theta(t) is the planar rocking block's, integrated on its own.
TEST(CylinderWorldFrame, PlanarMotionStaysInThePlaneAndFollowsTheRockingBlock) {
  const CylinderBody b = Body();
  const Planar p = PlanarOf(b);
  const double m = b.mass_kg;
  auto accel = [](double t) {
    return std::array<double, 3>{-2.5 * std::sin(3.0 * t), 0.0, 0.6 * std::sin(4.4 * t)};
  };
  auto rhs3 = [&](double t, const VecN<7>& y) {
    return VecN<7>(Derivative(b, y, accel(t), kG).dstate);
  };
  auto rhs_planar = [&](double t, const VecN<2>& y) {
    const std::array<double, 3> a = accel(t);
    const double th = y[0];
    return VecN<2>{
        y[1], m * p.rc_m *
                  ((kG + a[2]) * std::sin(th - p.alpha_rad) - a[0] * std::cos(th - p.alpha_rad)) /
                  p.io_kgm2};
  };
  constexpr double kTheta0 = 0.2, kThetaDot0 = 0.0, kEnd = 2.0;
  const Trajectory<2> planar =
      Integrate<2>(rhs_planar, VecN<2>{kTheta0, kThetaDot0}, kEnd, 1e-13, 1e-13);
  const CylinderState y0 = FromTiltAzimuthSpin(kTheta0, 0.0, 0.7, kThetaDot0, 0.0, 0.0);
  double tilt_y = 0.0, theta_err = 0.0, th_min = 1e9, n_min = 1e300;
  const Trajectory<7> run = Integrate<7>(rhs3, VecN<7>(y0), kEnd, 1e-13, 1e-13);
  for (size_t i = 0; i < run.t.size(); ++i) {
    const double t = run.t[i];
    const VecN<7>& y = run.y[i];
    const TiltAzimuthSpin a = ToTiltAzimuthSpin(y);
    tilt_y = std::max(tilt_y, std::abs(a.tilt_y_rad()));
    theta_err = std::max(theta_err, std::abs(a.tilt_x_rad() - planar.At(t)[0]));
    th_min = std::min(th_min, a.theta_rad);
    n_min = std::min(n_min, Derivative(b, y, accel(t), kG).normal_N());
  }
  std::printf(
      "planar trajectory: theta >= %.4f, N >= %.3f m g, |tilt_y| <= %.2e rad, "
      "|tilt_x - theta_planar| <= %.2e rad\n",
      th_min, n_min / (m * kG), tilt_y, theta_err);
  EXPECT_GT(th_min, 0.01);
  EXPECT_GT(n_min, 0.0);
  // Out of plane, only rounding (1e-16 per step) drives the motion: 1e-12 rad over 2 s.
  EXPECT_LT(tilt_y, 1e-12);
  // Two integrations at 1e-13 per step of the same motion, through dense outputs of 7th order.
  EXPECT_LT(theta_err, 1e-10);
}

// 5. Rotating the base's horizontal acceleration and the initial azimuth by beta about the
// vertical rotates the motion: phi(t) gains beta, theta(t) and psi(t) are unchanged.
TEST(CylinderWorldFrame, RotatingTheBaseMotionRotatesTheAzimuth) {
  const CylinderBody b = Body();
  constexpr double kBeta = 0.7, kEnd = 3.0;
  auto run = [&](double beta) {
    auto rhs = [&](double t, const VecN<7>& y) {
      return VecN<7>(Derivative(b, y, BaseAccel(t, beta), kG).dstate);
    };
    const CylinderState y0 = FromTiltAzimuthSpin(0.15, 0.3 + beta, -0.5, 0.0, 4.0, 0.5);
    return Integrate<7>(rhs, VecN<7>(y0), kEnd, 1e-13, 1e-13);
  };
  const Trajectory<7> a = run(0.0), c = run(kBeta);
  double phi_err = 0.0, theta_err = 0.0, psi_err = 0.0, th_min = 1e9, n_min = 1e300;
  double q_err = 0.0, omega_err = 0.0;
  for (size_t i = 0; i < a.t.size(); ++i) {
    const double t = a.t[i];
    const TiltAzimuthSpin x = ToTiltAzimuthSpin(a.y[i]);
    th_min = std::min(th_min, x.theta_rad);
    n_min = std::min(n_min, Derivative(b, a.y[i], BaseAccel(t, 0.0), kG).normal_N());
  }
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(kBeta, Eigen::Vector3d::UnitZ()));
  for (int j = 0; j <= 300; ++j) {
    const double t = kEnd * j / 300;
    const VecN<7> ya = a.At(t), yc = c.At(t);
    const TiltAzimuthSpin x = ToTiltAzimuthSpin(ya), z = ToTiltAzimuthSpin(yc);
    phi_err = std::max(phi_err, std::abs(AngleDiff(z.phi_rad, x.phi_rad + kBeta)));
    theta_err = std::max(theta_err, std::abs(z.theta_rad - x.theta_rad));
    psi_err = std::max(psi_err, std::abs(AngleDiff(z.psi_rad, x.psi_rad)));
    // The states themselves: q_c = Rz(beta) q_a, omega_c = Rz(beta) omega_a.
    const Eigen::Quaterniond qa(ya[0], ya[1], ya[2], ya[3]), qc(yc[0], yc[1], yc[2], yc[3]);
    q_err = std::max(q_err, ((turn * qa).coeffs() - qc.coeffs()).norm());
    omega_err = std::max(omega_err, (turn * AngularVelocityOf(ya) - AngularVelocityOf(yc)).norm());
  }
  std::printf(
      "rotated by %.1f rad: theta >= %.4f, N >= %.3f m g; |dphi - beta| <= %.2e, |dtheta| <= "
      "%.2e, |dpsi| <= %.2e rad, |q| %.2e, |omega| %.2e rad/s (%zu and %zu steps)\n",
      kBeta, th_min, n_min / (b.mass_kg * kG), phi_err, theta_err, psi_err, q_err, omega_err,
      a.t.size(), c.t.size());
  EXPECT_GT(th_min, 0.01);
  EXPECT_GT(n_min, 0.0);
  // The two runs take different steps, each with a local error of 1e-13 of the state: over ~500
  // steps, 1e-11 in the quaternion (size 1) and in omega per 1 rad/s of it (|omega| ~ 5 rad/s);
  // measured 2.6e-13 and 9.6e-12 rad/s ...
  EXPECT_LT(q_err, 1e-11);
  EXPECT_LT(omega_err, 1e-11 * 5.0);
  EXPECT_LT(theta_err, 1e-11);
  // ... which phi and psi carry divided by sin(theta) >= 0.0136: 1e-10 rad (measured 1e-11).
  EXPECT_LT(phi_err, 1e-10);
  EXPECT_LT(psi_err, 1e-10);
}

}  // namespace
}  // namespace rockbench::reference::test
