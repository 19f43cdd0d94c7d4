#include "motion/intensity.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "motion/ground_displacement.h"

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
  // PGV and PGD: the exact integrals of the piecewise-linear acceleration, zero outside the
  // samples (motion/ground_displacement.h); after the last sample a = 0 until t_end.
  const double t0 = c.t0_s();
  const double t_last = t0 + static_cast<double>(a.size() - 1) * dt;
  const GroundPeaks peaks = ExactGroundPeaks(a, dt, t_end_s - t_last);
  im.pgv_mps = peaks.velocity_mps;
  im.pgd_m = peaks.displacement_m;
  double arias = 0.0;
  std::vector<double> cumulative(a.size(), 0.0);  // integral of a^2 up to sample i
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i]) > im.pga_mps2) {
      im.pga_mps2 = std::abs(a[i]);
      im.pga_t_s = t0 + static_cast<double>(i) * dt;
    }
    if (i + 1 == a.size()) break;
    const double a0 = a[i], a1 = a[i + 1];
    arias += dt * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
    cumulative[i + 1] = arias;
  }
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

namespace {

// The times MeasureIntensity reads a component at over [0, t_end_s]: a record's samples up to
// its last at or before t_end_s, an analytic kind's SampleAnalytic points.
std::vector<double> IntensityTimes(const MotionComponent& c, double t_end_s) {
  std::vector<double> t;
  if (c.kind() == MotionKind::kFile) {
    const size_t n = c.samples_mps2().size();
    const double dt = c.dt_s();
    if (n == 0 || c.t0_s() >= t_end_s) return t;
    size_t keep = n;
    const double t_last = c.t0_s() + static_cast<double>(n) * dt - dt;
    if (t_last > t_end_s) {
      keep = std::min(static_cast<size_t>(std::floor((t_end_s - c.t0_s()) / dt)) + 1, n);
    }
    t.reserve(keep);
    for (size_t i = 0; i < keep; ++i) t.push_back(c.t0_s() + static_cast<double>(i) * dt);
    return t;
  }
  double dt = 0.0;
  const size_t n = SampleAnalytic(c, t_end_s, &dt).size();
  const double end = std::min(c.t0_s() + c.window_s(), t_end_s);
  for (size_t i = 0; i < n; ++i) {
    t.push_back(i + 1 == n ? end : c.t0_s() + static_cast<double>(i) * dt);
  }
  return t;
}

}  // namespace

ResultantPeak MeasureResultantPga(const std::optional<MotionComponent>& x,
                                  const std::optional<MotionComponent>& y, double t_end_s) {
  if (!(t_end_s > 0.0) || !std::isfinite(t_end_s)) {
    throw std::invalid_argument("intensity measures need a positive finite end time (s)");
  }
  ResultantPeak peak;
  const auto at = [](const std::optional<MotionComponent>& c, double t) {
    return c ? c->accel_mps2(t) : 0.0;
  };
  for (const std::optional<MotionComponent>* c : {&x, &y}) {
    if (!*c) continue;
    for (const double t : IntensityTimes(**c, t_end_s)) {
      const double a = std::hypot(at(x, t), at(y, t));
      if (a > peak.pga_mps2 || (a == peak.pga_mps2 && a > 0.0 && t < peak.t_s)) {
        peak.pga_mps2 = a;
        peak.t_s = t;
      }
    }
  }
  return peak;
}

}  // namespace rockbench
