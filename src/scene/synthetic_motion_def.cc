#include "scene/synthetic_motion_def.h"

#include <cmath>

#include "util/format.h"

namespace rockbench {
namespace {

std::string Num(double v) {
  return Format("%g", v);
}

}  // namespace

std::string SyntheticMotionProblem(const SyntheticMotionDef& d) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (d.target_peak_mps2 < 0.0 || !std::isfinite(d.target_peak_mps2)) {
    return "the target peak must be finite and >= 0, got " + Num(d.target_peak_mps2);
  }
  if (d.target_peak_mps2 == 0.0 && !positive(d.intensity_m2ps3)) {
    return "intensity must be > 0 (m^2/s^3), got " + Num(d.intensity_m2ps3);
  }
  if (!positive(d.dt_s)) return "dt must be > 0 (s), got " + Num(d.dt_s);
  if (!positive(d.duration_s)) return "duration_s must be > 0 (s), got " + Num(d.duration_s);
  if (d.duration_s / d.dt_s > 1e8) return "duration_s / dt must not exceed 1e8 samples";
  const double nyquist_hz = 0.5 / d.dt_s;
  if (!positive(d.ground_frequency_hz) || d.ground_frequency_hz >= nyquist_hz) {
    return "ground_frequency_hz must be > 0 and below the Nyquist frequency 1 / (2 dt) = " +
           Num(nyquist_hz) + " Hz, got " + Num(d.ground_frequency_hz);
  }
  if (!positive(d.ground_damping)) {
    return "ground_damping must be > 0, got " + Num(d.ground_damping);
  }
  if (d.filter_frequency_hz < 0.0 || !std::isfinite(d.filter_frequency_hz) ||
      d.filter_frequency_hz >= nyquist_hz) {
    return "filter_frequency_hz must be >= 0 (0: no Clough-Penzien filter) and below the "
           "Nyquist frequency " +
           Num(nyquist_hz) + " Hz, got " + Num(d.filter_frequency_hz);
  }
  if (d.filter_frequency_hz > 0.0 && !positive(d.filter_damping)) {
    return "filter_damping must be > 0, got " + Num(d.filter_damping);
  }
  if (d.high_pass_hz < 0.0 || !std::isfinite(d.high_pass_hz) || d.high_pass_hz >= nyquist_hz) {
    return "high_pass_hz must be >= 0 (0: no high-pass after the envelope) and below the "
           "Nyquist frequency " +
           Num(nyquist_hz) + " Hz, got " + Num(d.high_pass_hz);
  }
  if (d.envelope == SyntheticEnvelope::kJennings) {
    if (!positive(d.rise_s)) return "rise_s must be > 0 (s), got " + Num(d.rise_s);
    if (!(d.strong_end_s >= d.rise_s) || !std::isfinite(d.strong_end_s)) {
      return "strong_end_s must be >= rise_s (" + Num(d.rise_s) + " s), got " + Num(d.strong_end_s);
    }
    if (!positive(d.decay_per_s)) return "decay_per_s must be > 0 (1/s), got " + Num(d.decay_per_s);
  }
  return "";
}

}  // namespace rockbench
