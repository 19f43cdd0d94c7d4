#pragma once
// Housner's (1963) closed forms for a free-rocking rectangular block, used by every engine's
// tests: the rate at theta = 0 and the amplitude from energy, the coefficient of restitution
// from conservation of angular momentum about the landing corner, and the time of a quarter
// cycle from the energy quadrature. The block is scenes/housner_free_rocking.toml's.
#include <cmath>

namespace rockbench::testing_util {

// Housner's block of scenes/housner_free_rocking.toml: B = 1 m, H = 4 m.
constexpr double kB = 1.0, kH = 4.0, kG = 9.81;

struct Housner {
  double b = kB / 2, h = kH / 2;
  double R = std::hypot(b, h);
  double alpha = std::atan2(b, h);                      // theta_c
  double p2 = 3.0 * kG / (4.0 * R);                     // p^2 = m g R / I_O with I_O = 4/3 m R^2
  double e = 1.0 - 1.5 * std::pow(std::sin(alpha), 2);  // Housner's coefficient of restitution

  // |omega| at theta = 0 after release from rest at amplitude a (energy).
  double RateAtZero(double a) const {
    return std::sqrt(2.0 * p2 * (std::cos(alpha - a) - std::cos(alpha)));
  }
  // Amplitude reached from theta = 0 with rate w.
  double Amplitude(double w) const {
    return alpha - std::acos(std::cos(alpha) + w * w / (2.0 * p2));
  }
  // Time from rest at amplitude a to theta = 0: the energy quadrature
  // t = int_0^a dtheta / sqrt(2 p^2 (cos(alpha - a) - cos(alpha - theta))), with theta = a - u^2
  // removing the inverse-square-root end point; composite Simpson on u (smooth integrand).
  double QuarterTime(double a) const {
    const int n = 2000;
    const double U = std::sqrt(a), du = U / n;
    auto f = [&](double u) {
      if (u == 0.0) return 2.0 / std::sqrt(2.0 * p2 * std::sin(alpha - a));
      return 2.0 * u / std::sqrt(2.0 * p2 * (std::cos(alpha - a) - std::cos(alpha - a + u * u)));
    };
    double s = f(0.0) + f(U);
    for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(k * du);
    return s * du / 3.0;
  }
};

}  // namespace rockbench::testing_util
