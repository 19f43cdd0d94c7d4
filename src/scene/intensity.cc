#include "scene/intensity.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace rockbench {
namespace {

// Samples of an analytic kind on its window [t0, t0 + length] cut at t_end: 4000 per period
// (per pulse for a rectangular one), the window's ends on samples.
std::vector<double> SampleAnalytic(const MotionComponent& c, double t_end_s, double* dt_s) {
  const double t0 = c.t0_s();
  const double end = std::min(t0 + c.window_s(), t_end_s);
  if (!(end > t0)) return {};
  const double period =
      c.kind() == MotionKind::kRectangularPulse ? c.window_s() : 1.0 / c.frequency_hz();
  const double n_per = 4000.0;
  const auto n = static_cast<size_t>(std::ceil((end - t0) / period * n_per));
  *dt_s = (end - t0) / static_cast<double>(n);
  std::vector<double> a(n + 1);
  for (size_t i = 0; i <= n; ++i) {
    // The last sample exactly at the window's end (closed window).
    const double t = i == n ? end : t0 + static_cast<double>(i) * *dt_s;
    a[i] = c.accel_mps2(t);
  }
  return a;
}

// Peak |d| over one segment of length h that starts at (v, d) with acceleration a0 + s tau: at
// its end, and where v(tau) = v + a0 tau + s tau^2 / 2 vanishes inside.
double SegmentPeakDisplacement(double v, double d, double a0, double s, double h) {
  auto disp = [&](double tau) {
    return d + v * tau + a0 * tau * tau / 2 + s * tau * tau * tau / 6;
  };
  double peak = std::abs(disp(h));
  std::vector<double> roots;
  if (s == 0.0) {
    if (a0 != 0.0) roots.push_back(-v / a0);
  } else {
    const double disc = a0 * a0 - 2.0 * s * v;
    if (disc >= 0.0) {
      const double q = std::sqrt(disc);
      roots.push_back((-a0 + q) / s);
      roots.push_back((-a0 - q) / s);
    }
  }
  for (double tau : roots) {
    if (tau > 0.0 && tau < h) peak = std::max(peak, std::abs(disp(tau)));
  }
  return peak;
}

}  // namespace

IntensityMeasures MeasureIntensity(const MotionComponent& c, double t_end_s) {
  if (!(t_end_s > 0.0) || !std::isfinite(t_end_s)) {
    throw std::invalid_argument("intensity measures need a positive finite end time (s)");
  }
  IntensityMeasures im;
  double dt = c.dt_s();
  std::vector<double> a;
  if (c.kind() == MotionKind::kFile) {
    a = c.samples_mps2();
    // Cut at t_end: the samples up to it, then the interpolated value at t_end itself.
    const double t_last = c.t0_s() + static_cast<double>(a.size()) * dt - dt;
    if (t_last > t_end_s && c.t0_s() < t_end_s) {
      const auto keep = static_cast<size_t>(std::floor((t_end_s - c.t0_s()) / dt)) + 1;
      a.resize(std::min(keep, a.size()));
    } else if (c.t0_s() >= t_end_s) {
      a.clear();
    }
  } else {
    a = SampleAnalytic(c, t_end_s, &dt);
    switch (c.kind()) {
      case MotionKind::kSinePulse:
      case MotionKind::kCosinePulse:
      case MotionKind::kRicker:
        im.pulse_period_s = 1.0 / c.frequency_hz();
        break;
      case MotionKind::kRectangularPulse:
        im.pulse_period_s = c.window_s();
        break;
      default:
        break;
    }
  }
  if (a.empty()) return im;
  // Exact integrals of the piecewise-linear acceleration, zero outside the samples.
  const double t0 = c.t0_s();
  double v = 0.0, d = 0.0, arias = 0.0;
  std::vector<double> cumulative(a.size(), 0.0);  // integral of a^2 up to sample i
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i]) > im.pga_mps2) {
      im.pga_mps2 = std::abs(a[i]);
      im.pga_t_s = t0 + static_cast<double>(i) * dt;
    }
    if (i + 1 == a.size()) break;
    const double a0 = a[i], a1 = a[i + 1], s = (a1 - a0) / dt;
    // v's extreme inside the segment, where a crosses zero.
    if (a0 * a1 < 0.0) {
      const double tau = -a0 / s;
      im.pgv_mps = std::max(im.pgv_mps, std::abs(v + a0 * tau + s * tau * tau / 2));
    }
    im.pgd_m = std::max(im.pgd_m, SegmentPeakDisplacement(v, d, a0, s, dt));
    d += v * dt + dt * dt * (2.0 * a0 + a1) / 6.0;
    v += dt * (a0 + a1) / 2.0;
    im.pgv_mps = std::max(im.pgv_mps, std::abs(v));
    arias += dt * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
    cumulative[i + 1] = arias;
  }
  // After the last sample: a = 0, v constant, d linear until t_end.
  const double t_last = t0 + static_cast<double>(a.size() - 1) * dt;
  if (t_end_s > t_last) im.pgd_m = std::max(im.pgd_m, std::abs(d + v * (t_end_s - t_last)));
  im.arias_mps = std::numbers::pi / (2.0 * kStandardGravity_mps2) * arias;
  // D5-95 on the samples' cumulative integral, linear between samples.
  if (arias > 0.0) {
    auto time_at = [&](double fraction) {
      const double target = fraction * arias;
      const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
      const size_t k = static_cast<size_t>(it - cumulative.begin());
      if (k == 0) return t0;
      const double f = (target - cumulative[k - 1]) / (cumulative[k] - cumulative[k - 1]);
      return t0 + (static_cast<double>(k - 1) + f) * dt;
    };
    im.significant_duration_s = time_at(0.95) - time_at(0.05);
  }
  return im;
}

}  // namespace rockbench
