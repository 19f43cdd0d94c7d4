#include "motion/ground_displacement.h"

#include <algorithm>
#include <cmath>
#include <numbers>

// The engines' kinematic drive and the intensity measures come from here: every operation
// below is kept as it was in engines/common/engine_input.cc and motion/intensity.cc (same
// operations, same order), so that histories and measures keep their bits.

namespace rockbench {
namespace {

// Second-order Butterworth low-pass (bilinear transform with pre-warping), transposed direct
// form II. Runs over x in place; `steady` starts the filter in steady state for x[0].
void LowPassInPlace(std::vector<double>& x, double fc_hz, double dt_s, bool steady, bool reverse) {
  if (x.empty()) return;
  const double k = std::tan(std::numbers::pi * fc_hz * dt_s);
  const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k * k);
  const double b0 = k * k * norm, b1 = 2.0 * b0, b2 = b0;
  const double a1 = 2.0 * (k * k - 1.0) * norm, a2 = (1.0 - std::sqrt(2.0) * k + k * k) * norm;
  const size_t n = x.size();
  const double first = reverse ? x[n - 1] : x[0];
  double z1 = steady ? first * (1.0 - b0) : 0.0;
  double z2 = steady ? first * (b2 - a2) : 0.0;
  for (size_t i = 0; i < n; ++i) {
    double& v = reverse ? x[n - 1 - i] : x[i];
    const double in = v;
    const double out = b0 * in + z1;
    z1 = b1 * in - a1 * out + z2;
    z2 = b2 * in - a2 * out;
    v = out;
  }
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

std::int64_t StepCount(double duration_s, double dt_s) {
  return static_cast<std::int64_t>(std::max(0.0, std::ceil(duration_s / dt_s - 1e-9)));
}

void SampleGroundAcceleration(const GroundMotion& motion, double dt_s, std::size_t steps,
                              std::vector<double>* ax_mps2, std::vector<double>* ay_mps2) {
  ax_mps2->resize(steps);
  ay_mps2->resize(steps);
  for (std::size_t i = 0; i < steps; ++i) {
    const double t = static_cast<double>(i) * dt_s;
    (*ax_mps2)[i] = motion.xg_mps2(t);
    (*ay_mps2)[i] = motion.yg_mps2(t);
  }
}

GroundPath IntegrateGroundPath(const std::vector<double>& accel_mps2, double dt_s,
                               double highpass_hz) {
  GroundPath path;
  const size_t n = accel_mps2.size();
  std::vector<double> u(n + 1, 0.0);
  // Leapfrog double integration: the ground's second difference is exactly dt^2 a_n, the
  // velocity change the inertial drive gives the blocks in step n.
  double u_prev = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double next = 2.0 * u[i] - u_prev + dt_s * dt_s * accel_mps2[i];
    u_prev = u[i];
    u[i + 1] = next;
  }
  double peak = 0.0;
  for (double v : u) peak = std::max(peak, std::abs(v));
  path.raw_peak_m = peak;
  path.velocity_before_mps = 0.0;
  if (highpass_hz <= 0.0) {
    path.u_m = std::move(u);
    return path;
  }

  // Baseline: zero-phase low-pass of u. The 2nd-order Butterworth's envelope decays with time
  // constant 1 / (0.707 * 2 pi fc) = 0.225 / fc; pads of 1.2 / fc (5.3 time constants) let
  // the start-up transients of both passes die out before the data.
  const double pad_d = std::ceil(1.2 / (highpass_hz * dt_s));
  const size_t pad = static_cast<size_t>(std::min(pad_d, 5e7));
  std::vector<double> x(pad + u.size() + pad, 0.0);
  std::copy(u.begin(), u.end(), x.begin() + static_cast<std::ptrdiff_t>(pad));
  const double last = u.back();
  for (size_t k = 1; k <= pad; ++k) {
    // Odd reflection about the last sample (continues the final trend); beyond the record's
    // own length the reflection repeats its first value.
    const size_t mirror = k <= n ? n - k : 0;
    x[pad + n + k] = 2.0 * last - u[mirror];
  }
  LowPassInPlace(x, highpass_hz, dt_s, /*steady=*/false, /*reverse=*/false);
  LowPassInPlace(x, highpass_hz, dt_s, /*steady=*/true, /*reverse=*/true);
  std::vector<double> out(u.size());
  for (size_t i = 0; i < u.size(); ++i) out[i] = u[i] - x[pad + i];
  // u_{-1} = 0 before the record; its baseline value is x[pad - 1].
  const double u_minus1 = pad > 0 ? -x[pad - 1] : 0.0;
  path.velocity_before_mps = (out[0] - u_minus1) / dt_s;
  path.u_m = std::move(out);
  return path;
}

GroundPeaks ExactGroundPeaks(const std::vector<double>& a, double dt, double hold_s) {
  GroundPeaks peaks;
  double v = 0.0, d = 0.0;
  for (size_t i = 0; i + 1 < a.size(); ++i) {
    const double a0 = a[i], a1 = a[i + 1], s = (a1 - a0) / dt;
    // v's extreme inside the segment, where a crosses zero.
    if (a0 * a1 < 0.0) {
      const double tau = -a0 / s;
      peaks.velocity_mps = std::max(peaks.velocity_mps, std::abs(v + a0 * tau + s * tau * tau / 2));
    }
    peaks.displacement_m = std::max(peaks.displacement_m, SegmentPeakDisplacement(v, d, a0, s, dt));
    d += v * dt + dt * dt * (2.0 * a0 + a1) / 6.0;
    v += dt * (a0 + a1) / 2.0;
    peaks.velocity_mps = std::max(peaks.velocity_mps, std::abs(v));
  }
  // After the last sample: a = 0, v constant, d linear.
  if (hold_s > 0.0) peaks.displacement_m = std::max(peaks.displacement_m, std::abs(d + v * hold_s));
  return peaks;
}

}  // namespace rockbench
