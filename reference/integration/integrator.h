#pragma once
/// Explicit Runge-Kutta steps with dense output for a state of D components, the angles of the
/// blocks first, then their rates: y = (theta1, theta2, omega1, omega2) for the thesis's two
/// blocks (D = 4). Dormand-Prince 5(4) with its 4th-order continuous
/// extension (Hairer, Norsett & Wanner, "Solving ODEs I", II.6, as in dopri5.f), Dormand-Prince
/// 8(5,3) with its 7th-order continuous extension (the same book, II.10, as in dop853.f), and
/// the classical fixed-step RK4 of the thesis (eq. 6.2, 6.3) with cubic Hermite dense output.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "reference/integration/dop853_tableau.h"

namespace rockbench::reference {

/// A state of D components.
template <size_t D>
using VecN = std::array<double, D>;
/// The two blocks' state (theta1, theta2, omega1, omega2).
using Vec4 = VecN<4>;

/// The kinds of dense output, and one component of each (shared by every state size).
struct DenseKinds {
  enum Kind { kConstant, kDopri, kHermite, kDop853 };
  /// Number of coefficients of each component in a step of `kind`.
  static constexpr int Coefficients(Kind kind) {
    return kind == kDopri ? 5 : kind == kHermite ? 4 : kind == kDop853 ? 8 : 1;
  }
  /// The interpolants at s = (t - t0) / h, s1 = 1 - s, from one component's coefficients
  /// cf(0), cf(1), ... (one definition for Component and DenseStepN::At, so both give the
  /// same bits).
  template <class Coef>
  static double Dopri(double s, double s1, const Coef& cf) {
    return cf(0) + s * (cf(1) + s1 * (cf(2) + s * (cf(3) + s1 * cf(4))));
  }
  template <class Coef>
  static double Dop853(double s, double s1, const Coef& cf) {
    const double inner = cf(5) + s1 * (cf(6) + s * cf(7));
    return cf(0) + s * (cf(1) + s1 * (cf(2) + s * (cf(3) + s1 * (cf(4) + s * inner))));
  }
  /// Cubic Hermite on y0 = cf(0), y1 = cf(1), h f0 = cf(2), h f1 = cf(3).
  struct HermiteWeights {
    double h00, h10, h01, h11;
    HermiteWeights(double s, double s1)
        : h00((1 + 2 * s) * s1 * s1),
          h10(s * s1 * s1),
          h01(s * s * (3 - 2 * s)),
          h11(-s * s * s1) {}
    template <class Coef>
    double operator()(const Coef& cf) const {
      return h00 * cf(0) + h10 * cf(2) + h01 * cf(1) + h11 * cf(3);
    }
  };
  /// One component of the interpolant of a step of `kind` at s = (t - t0) / h, from its
  /// coefficients coef[0], coef[stride], ... (a kConstant step: coef[0]).
  static double Component(Kind kind, double s, const double* coef, size_t stride) {
    const double s1 = 1.0 - s;
    auto cf = [&](int j) { return coef[j * stride]; };
    if (kind == kDopri) return Dopri(s, s1, cf);
    if (kind == kDop853) return Dop853(s, s1, cf);
    if (kind == kHermite) return HermiteWeights(s, s1)(cf);
    return cf(0);
  }
};

/// Continuous output of one step on [t0, t0 + h].
template <size_t D>
struct DenseStepN : DenseKinds {
  using Vec = VecN<D>;
  Kind kind = kConstant;
  double t0 = 0.0, h = 0.0;
  /// kConstant: c[0]; kDopri: rcont1..5; kHermite: y0, y1, h f0, h f1; kDop853: y0 and the
  /// seven coefficients of dop853.f's contd8.
  std::array<Vec, 8> c{};
  /// An enclosure of the interpolant over the whole step: lo[i] <= At(t)[i] <= hi[i] for every
  /// t in [t0, t0 + h], rounding of At included. Every interpolant here is the chord from y0 to
  /// y1 plus s (1 - s) times a bounded remainder (s (1 - s) <= 1/4), so the enclosure is the
  /// chord's range widened by a quarter of the remainder's coefficients' magnitudes.
  void Bounds(Vec* lo, Vec* hi) const {
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    for (size_t i = 0; i < D; ++i) {
      double y0 = c[0][i], y1 = c[0][i], rest = 0.0, size = std::abs(c[0][i]);
      if (kind == kDopri || kind == kDop853) {
        // y0 + s c1 + s (1 - s) (c2 + s (c3 + ...)): y1 = y0 + c1.
        y1 = c[0][i] + c[1][i];
        const int last = kind == kDopri ? 4 : 7;
        for (int j = 2; j <= last; ++j) rest += std::abs(c[j][i]);
        size += std::abs(c[1][i]) + rest;
      } else if (kind == kHermite) {
        // y0 + s D + s (1 - s) ((1 - s) (h f0 - D) + s (D - h f1)) with D = y1 - y0.
        y1 = c[1][i];
        const double chord = c[1][i] - c[0][i];
        rest = std::abs(c[2][i] - chord) + std::abs(c[3][i] - chord);
        size += std::abs(c[1][i]) + std::abs(c[2][i]) + std::abs(c[3][i]);
      }
      // A few roundings of terms no larger than `size`; 64 ulps of it is far more.
      const double slack = 0.25 * rest + 64 * kEps * size;
      (*lo)[i] = std::min(y0, y1) - slack;
      (*hi)[i] = std::max(y0, y1) + slack;
    }
  }
  /// State at t (0 <= (t - t0) / h <= 1): Component for every component, the kind decided
  /// once (the same operations in the same order, so the same bits).
  Vec At(double t) const {
    if (kind == kConstant || h == 0.0) return c[0];
    const double s = (t - t0) / h, s1 = 1.0 - s;
    Vec y;
    if (kind == kDopri) {
      for (size_t i = 0; i < D; ++i) y[i] = Dopri(s, s1, [&](int j) { return c[j][i]; });
    } else if (kind == kDop853) {
      for (size_t i = 0; i < D; ++i) y[i] = Dop853(s, s1, [&](int j) { return c[j][i]; });
    } else {
      const HermiteWeights hermite(s, s1);
      for (size_t i = 0; i < D; ++i) y[i] = hermite([&](int j) { return c[j][i]; });
    }
    return y;
  }
};

using DenseStep = DenseStepN<4>;

/// Result of one step from (t, y) with step h.
template <size_t D>
struct StepResultN {
  VecN<D> y1{};
  VecN<D> f1{};      ///< f(t + h, y1) (first-same-as-last for the next step)
  double err = 0.0;  ///< scaled RMS error estimate (DOPRI only; <= 1 accepts)
  DenseStepN<D> dense;
};
using StepResult = StepResultN<4>;

/// One Dormand-Prince 5(4) step. f0 = f(t, y). rhs(t, y) -> VecN<D>. The error norm is the
/// root mean square over `active` components (D by default; a state padded with zeros beyond
/// its active components passes their count: the padding adds nothing to the sum).
// Out of line: a step is a loop of its own, compiled (and vectorised) apart from its caller's.
template <class Rhs, size_t D>
[[gnu::noinline]] StepResultN<D> Dopri5Step(const Rhs& rhs, double t, const VecN<D>& y,
                                            const VecN<D>& f0, double h, double rtol, double atol,
                                            int active = static_cast<int>(D)) {
  using Vec = VecN<D>;
  constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
  constexpr double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45, a42 = -56.0 / 15,
                   a43 = 32.0 / 9, a51 = 19372.0 / 6561, a52 = -25360.0 / 2187,
                   a53 = 64448.0 / 6561, a54 = -212.0 / 729, a61 = 9017.0 / 3168, a62 = -355.0 / 33,
                   a63 = 46732.0 / 5247, a64 = 49.0 / 176, a65 = -5103.0 / 18656, a71 = 35.0 / 384,
                   a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84;
  constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                   e6 = 22.0 / 525, e7 = -1.0 / 40;
  constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                   d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                   d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
  const Vec& k1 = f0;
  Vec yt;
  for (size_t i = 0; i < D; ++i) yt[i] = y[i] + h * a21 * k1[i];
  const Vec k2 = rhs(t + c2 * h, yt);
  for (size_t i = 0; i < D; ++i) yt[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
  const Vec k3 = rhs(t + c3 * h, yt);
  for (size_t i = 0; i < D; ++i) yt[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
  const Vec k4 = rhs(t + c4 * h, yt);
  for (size_t i = 0; i < D; ++i) {
    yt[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
  }
  const Vec k5 = rhs(t + c5 * h, yt);
  for (size_t i = 0; i < D; ++i) {
    yt[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
  }
  const Vec k6 = rhs(t + h, yt);
  StepResultN<D> r;
  for (size_t i = 0; i < D; ++i) {
    r.y1[i] = y[i] + h * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
  }
  const Vec k7 = rhs(t + h, r.y1);
  r.f1 = k7;
  double sum = 0.0;
  for (size_t i = 0; i < D; ++i) {
    const double e =
        h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
    const double sc = atol + rtol * std::max(std::abs(y[i]), std::abs(r.y1[i]));
    sum += (e / sc) * (e / sc);
  }
  r.err = std::sqrt(sum / active);
  r.dense.kind = DenseStepN<D>::kDopri;
  r.dense.t0 = t;
  r.dense.h = h;
  for (size_t i = 0; i < D; ++i) {
    const double ydiff = r.y1[i] - y[i];
    const double bspl = h * k1[i] - ydiff;
    r.dense.c[0][i] = y[i];
    r.dense.c[1][i] = ydiff;
    r.dense.c[2][i] = bspl;
    r.dense.c[3][i] = ydiff - h * k7[i] - bspl;
    r.dense.c[4][i] =
        h * (d1 * k1[i] + d3 * k3[i] + d4 * k4[i] + d5 * k5[i] + d6 * k6[i] + d7 * k7[i]);
  }
  return r;
}

/// One Dormand-Prince 8(5,3) step (dop853.f), the error norm over `active` components as
/// Dopri5Step's. f0 = f(t, y). 15 evaluations of rhs: 11 stages,
/// f(t + h, y1) and 3 for the 7th-order dense output. The error is dop853.f's: the 5th-order
/// estimate damped by the 3rd-order one, err = |h| e5^2 / sqrt(n (e5^2 + 0.01 e3^2)) with e5, e3
/// the scaled norms (<= 1 accepts).
// Out of line: a step is a loop of its own, compiled (and vectorised) apart from its caller's.
template <class Rhs, size_t D>
[[gnu::noinline]] StepResultN<D> Dop853Step(const Rhs& rhs, double t, const VecN<D>& y,
                                            const VecN<D>& f0, double h, double rtol, double atol,
                                            int active = static_cast<int>(D)) {
  using namespace dop853;
  using Vec = VecN<D>;
  std::array<Vec, 16> k;
  k[0] = f0;
  Vec yt;
  // The stages of the step (1-11), f(t + h, y1) (12) and the dense output's (13-15).
  auto stage = [&](int s) {
    for (size_t i = 0; i < D; ++i) {
      double sum = 0.0;
      for (int j = 0; j < s; ++j) sum += kA[s][j] * k[j][i];
      yt[i] = y[i] + h * sum;
    }
    k[s] = rhs(t + kC[s] * h, yt);
  };
  for (int s = 1; s < 12; ++s) stage(s);
  StepResultN<D> r;
  for (size_t i = 0; i < D; ++i) {
    double sum = 0.0;
    for (int j = 0; j < 12; ++j) sum += kA[12][j] * k[j][i];
    r.y1[i] = y[i] + h * sum;
  }
  double e5 = 0.0, e3 = 0.0;
  for (size_t i = 0; i < D; ++i) {
    double s5 = 0.0, s3 = 0.0;
    for (int j = 0; j < 12; ++j) {
      s5 += kE5[j] * k[j][i];
      s3 += kE3[j] * k[j][i];
    }
    const double sc = atol + rtol * std::max(std::abs(y[i]), std::abs(r.y1[i]));
    e5 += (s5 / sc) * (s5 / sc);
    e3 += (s3 / sc) * (s3 / sc);
  }
  const double deno = e5 + 0.01 * e3;
  r.err = deno > 0.0 ? std::abs(h) * e5 / std::sqrt(active * deno) : 0.0;
  k[12] = rhs(t + h, r.y1);
  r.f1 = k[12];
  for (int s = 13; s < 16; ++s) stage(s);
  r.dense.kind = DenseStepN<D>::kDop853;
  r.dense.t0 = t;
  r.dense.h = h;
  for (size_t i = 0; i < D; ++i) {
    const double ydiff = r.y1[i] - y[i];
    const double bspl = h * k[0][i] - ydiff;
    r.dense.c[0][i] = y[i];
    r.dense.c[1][i] = ydiff;
    r.dense.c[2][i] = bspl;
    r.dense.c[3][i] = ydiff - h * k[12][i] - bspl;
    for (int row = 0; row < 4; ++row) {
      double sum = 0.0;
      for (int j = 0; j < 16; ++j) sum += kD[row][j] * k[j][i];
      r.dense.c[4 + row][i] = h * sum;
    }
  }
  return r;
}

/// One classical RK4 step (thesis eq. 6.2). f0 = f(t, y). Dense output: cubic Hermite.
// Out of line: a step is a loop of its own, compiled (and vectorised) apart from its caller's.
template <class Rhs, size_t D>
[[gnu::noinline]] StepResultN<D> Rk4Step(const Rhs& rhs, double t, const VecN<D>& y,
                                         const VecN<D>& f0, double h) {
  using Vec = VecN<D>;
  Vec yt;
  const Vec& k1 = f0;
  for (size_t i = 0; i < D; ++i) yt[i] = y[i] + 0.5 * h * k1[i];
  const Vec k2 = rhs(t + 0.5 * h, yt);
  for (size_t i = 0; i < D; ++i) yt[i] = y[i] + 0.5 * h * k2[i];
  const Vec k3 = rhs(t + 0.5 * h, yt);
  for (size_t i = 0; i < D; ++i) yt[i] = y[i] + h * k3[i];
  const Vec k4 = rhs(t + h, yt);
  StepResultN<D> r;
  for (size_t i = 0; i < D; ++i) r.y1[i] = y[i] + h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  r.f1 = rhs(t + h, r.y1);
  r.dense.kind = DenseStepN<D>::kHermite;
  r.dense.t0 = t;
  r.dense.h = h;
  for (size_t i = 0; i < D; ++i) {
    r.dense.c[0][i] = y[i];
    r.dense.c[1][i] = r.y1[i];
    r.dense.c[2][i] = h * f0[i];
    r.dense.c[3][i] = h * r.f1[i];
  }
  return r;
}

/// Brent's method for a root of f in [a, b] with f(a) f(b) <= 0, to |b - a| <= tol.
/// Returns the bracket (lo, hi) with the root inside: lo on f(a)'s side, hi on f(b)'s side.
template <class F>
std::pair<double, double> BrentBracket(const F& f, double a, double b, double fa, double fb,
                                       double tol) {
  // Regula falsi (Illinois) with bisection safeguard: keeps a strict bracket.
  double lo = a, hi = b, flo = fa, fhi = fb;
  int side = 0;
  for (int it = 0; it < 400 && hi - lo > tol; ++it) {
    double m = (flo * hi - fhi * lo) / (flo - fhi);
    if (!(m > lo && m < hi) || it % 4 == 3) m = 0.5 * (lo + hi);
    const double fm = f(m);
    if ((fm > 0) == (flo > 0) && fm != 0.0) {
      lo = m;
      flo = fm;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = m;
      fhi = fm;
      if (side == 1) flo *= 0.5;
      side = 1;
      if (fm == 0.0) {
        lo = m;  // an exact root: a zero-width bracket
        break;
      }
    }
  }
  return {lo, hi};
}

}  // namespace rockbench::reference
