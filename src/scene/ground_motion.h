#pragma once
/// Base (ground) motion: horizontal and vertical acceleration histories xg''(t), yg''(t).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace rockbench {

/// What was read: reported in summary.json as base.horizontal / base.vertical.
struct MotionInfo {
  std::string source;      ///< file path as written in the scene, or "harmonic", ...
  std::string format;      ///< "AT2", "plain-2col", "plain-1col", "analytic" or "samples"
                           ///< (built in code with FromSamples)
  int npts = 0;            ///< samples (0 for analytic kinds)
  double dt_s = 0.0;       ///< sample interval (0 for analytic kinds)
  double duration_s = 0.0; ///< last sample time - first (analytic: pulse length, inf allowed)
  double peak_g = 0.0;     ///< peak |acceleration| after units and scale, in g (records: the
                           ///< largest |sample|; analytic kinds: exact, from the formula)
  double peak_t_s = 0.0;   ///< time of the peak (the first one if several)
  int padded_samples = 0;  ///< zeros appended to match the other component's length
};

/// One acceleration component. A record is piecewise linear between samples, zero before its
/// first sample (at start_s; for a two-column file its own first time plus start_s) and after
/// its last; at exactly a sample time it is that sample. Analytic kinds, with A = amplitude_g *
/// scale * g, f = frequency_hz, t0 = start_s, zero outside the closed window given:
/// - harmonic:          A sin(2 pi f (t - t0))            on [t0, t0 + duration_s] (default inf)
/// - sine_pulse:        A sin(2 pi f (t - t0))            on [t0, t0 + 1/f]
/// - cosine_pulse:      A cos(2 pi f (t - t0))            on [t0, t0 + 1/f]
/// - rectangular_pulse: A                                 on [t0, t0 + duration_s]
/// - ricker:            A (1 - 2 pi^2 f^2 tau^2) exp(-pi^2 f^2 tau^2), tau = t - t0 - 1/f,
///                                                        on [t0, t0 + 2/f] (peak A at t0 + 1/f)
class MotionComponent {
 public:
  /// Builds from a scene definition (reads the file when kind is kFile). Throws SceneError
  /// naming the file, line and what was expected.
  static MotionComponent FromDef(const MotionDef& def, double gravity_mps2);
  /// A sampled record in m/s^2, first sample at t0_s.
  static MotionComponent FromSamples(std::vector<double> accel_mps2, double dt_s, double t0_s,
                                     double gravity_mps2, std::string source);

  /// Acceleration at t, m/s^2.
  double accel_mps2(double t_s) const;
  /// The first kink or jump strictly after t_s (a sample time, pulse start or end); +inf if none.
  double next_breakpoint_after(double t_s) const;
  /// End of the motion (last sample, pulse end; +inf for a never-ending harmonic).
  double end_s() const;
  const MotionInfo& info() const { return info_; }
  /// Appends zero samples so that the record lasts until t_end_s (records only).
  void pad_to(double t_end_s);
  /// Samples of a record (empty for analytic kinds).
  const std::vector<double>& samples_mps2() const { return samples_; }
  double t0_s() const { return t0_; }
  double dt_s() const { return dt_; }

 private:
  MotionKind kind_ = MotionKind::kFile;
  std::vector<double> samples_;  // m/s^2
  double t0_ = 0.0, dt_ = 0.0;
  double amplitude_mps2_ = 0.0, frequency_hz_ = 0.0, duration_s_ = 0.0;
  MotionInfo info_;
};

/// The base motion of a scene: optional horizontal and vertical components.
class GroundMotion {
 public:
  GroundMotion() = default;
  /// Builds both components of a scene (none when the scene has no [base] table). Components of
  /// different lengths are padded with zeros to the longer one (info().padded_samples says so).
  static GroundMotion FromScene(const Scene& scene);

  double xg_mps2(double t_s) const { return horizontal_ ? horizontal_->accel_mps2(t_s) : 0.0; }
  double yg_mps2(double t_s) const { return vertical_ ? vertical_->accel_mps2(t_s) : 0.0; }
  /// The earliest kink of either component strictly after t_s; +inf if none.
  double next_breakpoint_after(double t_s) const;
  /// Time after which both components are zero (0 for no motion, +inf for endless harmonic).
  double end_s() const;
  bool has_horizontal() const { return horizontal_.has_value(); }
  bool has_vertical() const { return vertical_.has_value(); }
  bool empty() const { return !horizontal_ && !vertical_; }
  const std::optional<MotionComponent>& horizontal() const { return horizontal_; }
  const std::optional<MotionComponent>& vertical() const { return vertical_; }
  void set_horizontal(MotionComponent c) { horizontal_ = std::move(c); }
  void set_vertical(MotionComponent c) { vertical_ = std::move(c); }

 private:
  std::optional<MotionComponent> horizontal_, vertical_;
};

/// A record as read from a file, before units and scale.
struct RecordData {
  std::vector<double> values;  ///< acceleration in the file's units
  double dt_s = 0.0;
  double t0_s = 0.0;           ///< time of the first sample in the file (two-column files)
  std::string format;          ///< "AT2", "plain-2col", "plain-1col"
  bool units_are_g = false;    ///< AT2 header said UNITS OF G
  int units_line = 0;          ///< AT2: line number of the "UNITS OF G" header line (0: none)
};

/// Reads a PEER AT2 file (all header variants of records/SOURCES.md). Throws SceneError.
RecordData ReadAt2(const std::filesystem::path& path);
/// Reads a plain file: two columns (t, a) or one column (a, dt given by dt_s > 0), with optional
/// non-numeric header lines. Throws SceneError.
RecordData ReadPlain(const std::filesystem::path& path, double dt_s);

}  // namespace rockbench
