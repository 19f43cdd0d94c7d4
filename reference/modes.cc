#include "reference/modes.h"

#include <cmath>

namespace rockbench::reference {
namespace {

// Solves [a b; c d] x = [e f].
std::array<double, 2> Solve2(double a, double b, double c, double d, double e, double f) {
  const double det = a * d - b * c;
  return {(e * d - b * f) / det, (a * f - c * e) / det};
}

// Sines and cosines of (theta - offset): exact, or linearized about theta = 0 to first order
// (sin(theta - a) ~ theta cos a - sin a, cos(theta - a) ~ cos a + theta sin a).
struct Trig {
  bool linear;
  double sin_of(double theta, double a) const {
    return linear ? theta * std::cos(a) - std::sin(a) : std::sin(theta - a);
  }
  double cos_of(double theta, double a) const {
    // The linearized equations keep only the theta = 0 value of the base-acceleration lever arm
    // (thesis eq. 3.32 drops the theta sin(theta_c) xg'' term).
    return linear ? std::cos(a) : std::cos(theta - a);
  }
};

}  // namespace

std::array<double, 2> ModeAccelerations(const Geometry& geo, Mode mode, const State& s, double xg,
                                        double yg, Equations equations) {
  const Trig tr{equations == Equations::kLinearized};
  const bool linear = tr.linear;
  const BlockProps& p1 = geo.block1;
  const BlockProps& p2 = geo.block2;
  const double m1 = p1.m, m2 = p2.m, r1 = p1.r, r2 = p2.r;
  const double g = geo.g;
  const double t1 = s.theta1, t2 = s.theta2;
  switch (mode) {
    case Mode::kRest:
      return {0.0, 0.0};
    case Mode::k3a:
    case Mode::k3b: {
      // Eq. 4.39: I_O th'' - M R g sin(th - S th_c) = -M R [xg'' cos(th - S th_c)
      //                                                    - yg'' sin(th - S th_c)].
      const double S = mode == Mode::k3a ? 1.0 : -1.0;
      const double a = S * geo.theta_c;
      const double MR = geo.M * geo.R;
      const double acc = (MR * (g + yg) * tr.sin_of(t1, a) - MR * xg * tr.cos_of(t1, a)) / geo.I_O;
      return {acc, acc};
    }
    case Mode::k4a:
    case Mode::k4b: {
      // Eq. 4.42 (S is the sign of theta2, printed as S_theta1; I_O2 printed as I_O1).
      const double S = mode == Mode::k4a ? 1.0 : -1.0;
      const double a = S * p2.theta_c;
      const double acc =
          (m2 * r2 * (g + yg) * tr.sin_of(t2, a) - m2 * r2 * xg * tr.cos_of(t2, a)) / p2.I_O;
      return {0.0, acc};
    }
    case Mode::k1a:
    case Mode::k1b: {
      // Eq. 4.23 with gamma1 = theta1 - theta2 + S (theta_c2 - beta) (4.20; 4.24 prints
      // theta_c1) and block 2's own theta_c2 and I_O2 in its row.
      const double S = mode == Mode::k1a ? 1.0 : -1.0;
      const double l = geo.l, beta = geo.beta;
      const double gam = linear ? S * (p2.theta_c - beta) : t1 - t2 + S * (p2.theta_c - beta);
      const double cg = std::cos(gam), sg = linear ? 0.0 : std::sin(gam);
      const double a11 = p1.I_O + m2 * l * l, a12 = m2 * r2 * l * cg;
      const double a21 = a12, a22 = p2.I_O;
      const double ge = g + yg;
      const double f1 =
          -m2 * r2 * l * sg * s.omega2 * s.omega2 + m1 * r1 * ge * tr.sin_of(t1, S * p1.theta_c) +
          m2 * l * ge * tr.sin_of(t1, S * beta) -
          (m1 * r1 * tr.cos_of(t1, S * p1.theta_c) + m2 * l * tr.cos_of(t1, S * beta)) * xg;
      const double f2 = m2 * r2 * l * sg * s.omega1 * s.omega1 +
                        m2 * r2 * ge * tr.sin_of(t2, S * p2.theta_c) -
                        m2 * r2 * tr.cos_of(t2, S * p2.theta_c) * xg;
      return Solve2(a11, a12, a21, a22, f1, f2);
    }
    case Mode::k2a:
    case Mode::k2b: {
      // Eq. 4.35 with l', beta' throughout (the OCR prints l and beta in places) and
      // gamma2 = theta1 - theta2 - S (theta_c2 + beta') (4.32).
      const double S = mode == Mode::k2a ? 1.0 : -1.0;
      const double l = geo.l_p, beta = geo.beta_p;
      const double gam = linear ? -S * (p2.theta_c + beta) : t1 - t2 - S * (p2.theta_c + beta);
      const double cg = std::cos(gam), sg = linear ? 0.0 : std::sin(gam);
      const double a11 = p1.I_O + m2 * l * l, a12 = m2 * r2 * l * cg;
      const double a21 = a12, a22 = p2.I_O;
      const double ge = g + yg;
      const double f1 =
          -m2 * r2 * l * sg * s.omega2 * s.omega2 + m1 * r1 * ge * tr.sin_of(t1, S * p1.theta_c) +
          m2 * l * ge * tr.sin_of(t1, S * beta) -
          (m1 * r1 * tr.cos_of(t1, S * p1.theta_c) + m2 * l * tr.cos_of(t1, S * beta)) * xg;
      const double f2 = m2 * r2 * l * sg * s.omega1 * s.omega1 +
                        m2 * r2 * ge * tr.sin_of(t2, -S * p2.theta_c) -
                        m2 * r2 * tr.cos_of(t2, -S * p2.theta_c) * xg;
      return Solve2(a11, a12, a21, a22, f1, f2);
    }
  }
  return {0.0, 0.0};
}

}  // namespace rockbench::reference
