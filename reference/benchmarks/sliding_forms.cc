#include "reference/benchmarks/sliding_forms.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace rockbench::benchmarks {
namespace {

void Require(bool ok, const char* what) {
  if (!ok) throw std::domain_error(what);
}

// The flight's rate z'(t), m/s.
double FlightRate_mps(double t_s, double eps, double omega, double g) {
  const double t0 = std::asin(1.0 / (1.0 + eps)) / omega;
  return -g * (t_s - t0) - g * (1.0 + eps) * (std::cos(omega * t_s) - std::cos(omega * t0)) / omega;
}

// The root of f in [lo, hi] (f(lo) and f(hi) of opposite signs), to the last bits: GSL's Brent.
double Root(const std::function<double(double)>& f, double lo, double hi) {
  gsl_function fn;
  fn.function = [](double x, void* p) {
    return (*static_cast<const std::function<double(double)>*>(p))(x);
  };
  fn.params = const_cast<std::function<double(double)>*>(&f);
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(s, &fn, lo, hi);
  double x = 0.5 * (lo + hi);
  for (int i = 0; i < 200; ++i) {
    gsl_root_fsolver_iterate(s);
    x = gsl_root_fsolver_root(s);
    const double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(a, b, 0.0, 4e-16) == GSL_SUCCESS) break;
  }
  gsl_root_fsolver_free(s);
  return x;
}

}  // namespace

SlidingPulse SlidingBlockUnderPulse(double a_mps2, double pulse_s, double mu, double g_mps2) {
  Require(
      std::isfinite(a_mps2) && std::isfinite(pulse_s) && std::isfinite(mu) && std::isfinite(g_mps2),
      "SlidingBlockUnderPulse: every argument must be finite");
  Require(pulse_s > 0.0 && mu > 0.0 && g_mps2 > 0.0,
          "SlidingBlockUnderPulse: the pulse, mu and g must be positive");
  SlidingPulse out;
  const double a = std::abs(a_mps2), f = mu * g_mps2, sign = a_mps2 > 0.0 ? 1.0 : -1.0;
  if (a <= f) return out;
  out.slides = true;
  out.stick_t_s = a * pulse_s / f;
  out.peak_slip_rate_mps = -sign * (a - f) * pulse_s;
  out.slip_m = -sign * (a - f) * a * pulse_s * pulse_s / (2.0 * f);
  return out;
}

double FlightHeight_m(double t_s, double eps, double omega, double g) {
  const double t0 = std::asin(1.0 / (1.0 + eps)) / omega, s = t_s - t0;
  return -0.5 * g * s * s - g * (1.0 + eps) *
                                ((std::sin(omega * t_s) - std::sin(omega * t0)) / (omega * omega) -
                                 std::cos(omega * t0) * s / omega);
}

LiftOff LiftOffUnderVerticalSine(double eps, double omega, double g) {
  Require(std::isfinite(eps) && std::isfinite(omega) && std::isfinite(g),
          "LiftOffUnderVerticalSine: every argument must be finite");
  Require(eps > 0.0 && omega > 0.0 && g > 0.0,
          "LiftOffUnderVerticalSine: eps, omega and g must be positive");
  LiftOff out;
  out.off_t_s = std::asin(1.0 / (1.0 + eps)) / omega;
  // z grows as (t - t_off)^3 at first (z'' = 0 at t_off) and falls on average at g: scan by a
  // hundredth of a period for the first sign change of z, then of z' before it (the peak).
  const double step = 2.0 * M_PI / omega / 100.0;
  const auto z = [&](double t) { return FlightHeight_m(t, eps, omega, g); };
  const auto zr = [&](double t) { return FlightRate_mps(t, eps, omega, g); };
  double lo = out.off_t_s + step;
  Require(z(lo) > 0.0, "LiftOffUnderVerticalSine: eps too small for a scan step of T/100");
  double hi = lo + step;
  for (int i = 0; z(hi) > 0.0; ++i) {
    Require(i < 1000000, "LiftOffUnderVerticalSine: no landing found");
    lo = hi;
    hi += step;
  }
  out.land_t_s = Root(z, lo, hi);
  out.landing_rate_mps = zr(out.land_t_s);
  // The peak: the largest z at a root of z' (+ to -) between lift-off and landing.
  double a = out.off_t_s + step;
  while (a < out.land_t_s) {
    const double b = std::min(a + step, out.land_t_s);
    if (zr(a) > 0.0 && zr(b) <= 0.0)
      out.peak_height_m = std::max(out.peak_height_m, z(Root(zr, a, b)));
    a = b;
  }
  return out;
}

}  // namespace rockbench::benchmarks
