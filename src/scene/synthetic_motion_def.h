#pragma once
/// What a scene says of a synthetic ground motion (kind = "kanai_tajimi"): the process's
/// parameters. The process itself, its generator and its spectra: motion/synthetic_motion.h.
#include <cstdint>
#include <string>

namespace rockbench {

/// The envelope e(t) of the stationary process, t from the record's start.
enum class SyntheticEnvelope {
  kNone,      ///< e = 1: the stationary process itself (after the filters' start from rest)
  kJennings,  ///< (t / rise)^2 before rise, 1 until strong_end, exp(-decay (t - strong_end)) after
};

/// The definition of one synthetic component (the [base.horizontal] or [base.vertical] keys of
/// kind = "kanai_tajimi").
struct SyntheticMotionDef {
  /// S0, two-sided PSD of the bedrock white noise, m^2/s^3 (the omega convention above). Used
  /// when target_peak_mps2 is 0.
  double intensity_m2ps3 = 0.0;
  /// When > 0: the record is scaled so that its peak |acceleration| is this, m/s^2 (the
  /// intensity is then irrelevant).
  double target_peak_mps2 = 0.0;
  double ground_frequency_hz = 2.5;  ///< w_g / 2 pi, Hz (firm soil ~2.5 Hz)
  double ground_damping = 0.6;       ///< z_g
  double filter_frequency_hz = 0.0;  ///< w_f / 2 pi, Hz; 0: no Clough-Penzien filter
  double filter_damping = 0.6;       ///< z_f
  /// w_c / 2 pi of the high-pass after the envelope, Hz; 0: none. 0.1 Hz keeps the periods
  /// that rock metre-sized blocks (their p / 2 pi is 0.3 to 0.5 Hz) and removes the drift.
  double high_pass_hz = 0.1;
  /// Correct the record so that its end velocity and displacement are zero (see above).
  bool zero_residuals = true;
  SyntheticEnvelope envelope = SyntheticEnvelope::kJennings;
  double rise_s = 2.0;         ///< Jennings: end of the quadratic rise, s
  double strong_end_s = 10.0;  ///< Jennings: end of the strong phase, s
  double decay_per_s = 0.3;    ///< Jennings: exponential decay rate after it, 1/s
  double dt_s = 0.005;         ///< sample interval, s
  double duration_s = 20.0;    ///< the record's length, s (samples at 0, dt, ..., duration)
  std::uint64_t seed = 1;      ///< the random stream
};

/// Checks a definition; returns an empty string when it is valid, else what is wrong, naming
/// the key ("ground_damping must be > 0, got -1").
std::string SyntheticMotionProblem(const SyntheticMotionDef& def);

}  // namespace rockbench
