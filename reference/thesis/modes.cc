#include "reference/thesis/modes.h"

#include <cmath>

namespace rockbench::reference {
namespace {

// Solves [a b; c d] x = [e f].
std::array<double, 2> Solve2(double a, double b, double c, double d, double e, double f) {
  const double det = a * d - b * c;
  return {(e * d - b * f) / det, (a * f - c * e) / det};
}

// Sines and cosines of (theta - S a) for a constant angle a (its SinCos from the geometry) and a
// sign S, from theta's own sine and cosine by the angle-difference formulas; or linearized about
// theta = 0 to first order (sin(theta - a) ~ theta cos a - sin a, cos(theta - a) ~ cos a).
struct Trig {
  bool linear;
  double sin_theta, cos_theta, theta;
  double sin_of(double S, SinCos a) const {
    return linear ? theta * a.cos - S * a.sin : sin_theta * a.cos - cos_theta * (S * a.sin);
  }
  double cos_of(double S, SinCos a) const {
    // The linearized equations keep only the theta = 0 value of the base-acceleration lever arm
    // (thesis eq. 3.32 drops the theta sin(theta_c) xg'' term).
    return linear ? a.cos : cos_theta * a.cos + sin_theta * (S * a.sin);
  }
};

// Sine and cosine of gamma = theta1 - theta2 + S k (a constant k, its SinCos from the geometry);
// linearized: gamma = S k.
SinCos GammaTrig(bool linear, const Tilts& tl, double S, SinCos k) {
  if (linear) return {0.0, k.cos};
  const double sin_d = tl.sin1 * tl.cos2 - tl.cos1 * tl.sin2;  // sin(theta1 - theta2)
  const double cos_d = tl.cos1 * tl.cos2 + tl.sin1 * tl.sin2;
  return {sin_d * k.cos + cos_d * (S * k.sin), cos_d * k.cos - sin_d * (S * k.sin)};
}

// The two-degree-of-freedom modes (1 and 2) share their form: a 2x2 mass matrix with the
// coupling m2 r2 l cos(gamma) and the gyroscopic terms m2 r2 l sin(gamma) omega^2.
std::array<double, 2> TwoDofAccelerations(const Geometry& geo, const State& s, const Tilts& tl,
                                          bool linear, double S, double l, SinCos beta,
                                          SinCos gamma, double S2, double xg, double yg) {
  const BlockProps& p1 = geo.block1;
  const BlockProps& p2 = geo.block2;
  const double m1 = p1.m, m2 = p2.m, r1 = p1.r, r2 = p2.r;
  const Trig tr1{linear, tl.sin1, tl.cos1, s.theta1};
  const Trig tr2{linear, tl.sin2, tl.cos2, s.theta2};
  const double cg = gamma.cos, sg = gamma.sin;
  const double a11 = p1.I_O + m2 * l * l, a12 = m2 * r2 * l * cg;
  const double a21 = a12, a22 = p2.I_O;
  const double ge = geo.g + yg;
  const double f1 = -m2 * r2 * l * sg * s.omega2 * s.omega2 +
                    m1 * r1 * ge * tr1.sin_of(S, geo.trig_c1) + m2 * l * ge * tr1.sin_of(S, beta) -
                    (m1 * r1 * tr1.cos_of(S, geo.trig_c1) + m2 * l * tr1.cos_of(S, beta)) * xg;
  const double f2 = m2 * r2 * l * sg * s.omega1 * s.omega1 +
                    m2 * r2 * ge * tr2.sin_of(S2, geo.trig_c2) -
                    m2 * r2 * tr2.cos_of(S2, geo.trig_c2) * xg;
  return Solve2(a11, a12, a21, a22, f1, f2);
}

}  // namespace

std::array<double, 2> ModeAccelerations(const Geometry& geo, Mode mode, const State& s, double xg,
                                        double yg, Equations equations) {
  // Only the tilts the mode's equations use are taken (mode 3: theta1's, mode 4: theta2's).
  Tilts tl;
  const Contacts c = ContactsOf(mode);
  const bool linear = equations == Equations::kLinearized;
  if (!linear && c.ground != Contact::kFace) {
    tl.sin1 = std::sin(s.theta1);
    tl.cos1 = std::cos(s.theta1);
  }
  if (!linear && c.interface != Contact::kFace && geo.two_blocks) {
    tl.sin2 = std::sin(s.theta2);
    tl.cos2 = std::cos(s.theta2);
  }
  return ModeAccelerations(geo, mode, s, tl, xg, yg, equations);
}

std::array<double, 2> ModeAccelerations(const Geometry& geo, Mode mode, const State& s,
                                        const Tilts& tl, double xg, double yg,
                                        Equations equations) {
  const bool linear = equations == Equations::kLinearized;
  const BlockProps& p2 = geo.block2;
  const double m2 = p2.m, r2 = p2.r;
  const double g = geo.g;
  switch (mode) {
    case Mode::kRest:
      return {0.0, 0.0};
    case Mode::k3a:
    case Mode::k3b: {
      // Eq. 4.39: I_O th'' - M R g sin(th - S th_c) = -M R [xg'' cos(th - S th_c)
      //                                                    - yg'' sin(th - S th_c)].
      const double S = mode == Mode::k3a ? 1.0 : -1.0;
      const Trig tr{linear, tl.sin1, tl.cos1, s.theta1};
      const double MR = geo.M * geo.R;
      const double acc = (MR * (g + yg) * tr.sin_of(S, geo.trig_c_stack) -
                          MR * xg * tr.cos_of(S, geo.trig_c_stack)) /
                         geo.I_O;
      return {acc, acc};
    }
    case Mode::k4a:
    case Mode::k4b: {
      // Eq. 4.42 (S is the sign of theta2, printed as S_theta1; I_O2 printed as I_O1).
      const double S = mode == Mode::k4a ? 1.0 : -1.0;
      const Trig tr{linear, tl.sin2, tl.cos2, s.theta2};
      const double acc = (m2 * r2 * (g + yg) * tr.sin_of(S, geo.trig_c2) -
                          m2 * r2 * xg * tr.cos_of(S, geo.trig_c2)) /
                         p2.I_O;
      return {0.0, acc};
    }
    case Mode::k1a:
    case Mode::k1b: {
      // Eq. 4.23 with gamma1 = theta1 - theta2 + S (theta_c2 - beta) (4.20; 4.24 prints
      // theta_c1) and block 2's own theta_c2 and I_O2 in its row.
      const double S = mode == Mode::k1a ? 1.0 : -1.0;
      return TwoDofAccelerations(geo, s, tl, linear, S, geo.l, geo.trig_beta,
                                 GammaTrig(linear, tl, S, geo.trig_gamma1), S, xg, yg);
    }
    case Mode::k2a:
    case Mode::k2b: {
      // Eq. 4.35 with l', beta' throughout (the OCR prints l and beta in places) and
      // gamma2 = theta1 - theta2 - S (theta_c2 + beta') (4.32); block 2 pivots on the
      // opposite side (-S theta_c2).
      const double S = mode == Mode::k2a ? 1.0 : -1.0;
      return TwoDofAccelerations(geo, s, tl, linear, S, geo.l_p, geo.trig_beta_p,
                                 GammaTrig(linear, tl, -S, geo.trig_gamma2), -S, xg, yg);
    }
  }
  return {0.0, 0.0};
}

}  // namespace rockbench::reference
