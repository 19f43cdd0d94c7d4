#pragma once
/// Base (ground) motion: acceleration histories along +x (horizontal), +y (transverse, 3-D
/// bodies only) and up (vertical).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace rockbench {

struct RecordData;

/// What was read: reported in summary.json as base.horizontal / base.vertical.
struct MotionInfo {
  std::string source;       ///< file path as written in the scene, or "harmonic", ...
  std::string format;       ///< "AT2", "plain-2col", "plain-1col", "analytic" or "samples"
                            ///< (built in code with FromSamples)
  int npts = 0;             ///< samples (0 for analytic kinds)
  double dt_s = 0.0;        ///< sample interval (0 for analytic kinds)
  double duration_s = 0.0;  ///< last sample time - first (analytic: pulse length, inf allowed)
  double peak_g = 0.0;      ///< peak |acceleration| after units and scale, in standard g
                            ///< (kStandardGravity_mps2; records: the largest |sample|;
                            ///< analytic kinds: exact, from the formula)
  double peak_t_s = 0.0;    ///< time of the peak (the first one if several)
  int padded_samples = 0;   ///< zeros appended to match the other component's length
};

/// One acceleration component. A record is piecewise linear between samples, zero before its
/// first sample (at start_s; for a two-column file its own first time plus start_s) and after
/// its last; at exactly a sample time it is that sample. Analytic kinds, with A = amplitude_g *
/// scale * kStandardGravity_mps2 (g is standard gravity, whatever the scene's [run] gravity),
/// f = frequency_hz, t0 = start_s, zero outside the closed window given:
/// - harmonic:          A sin(2 pi f (t - t0) + phase)    on [t0, t0 + duration_s] (default inf;
///                                                        phase = phase_deg, default 0)
/// - sine_pulse:        A sin(2 pi f (t - t0))            on [t0, t0 + 1/f]
/// - cosine_pulse:      A cos(2 pi f (t - t0))            on [t0, t0 + 1/f]
/// - rectangular_pulse: A                                 on [t0, t0 + duration_s]
/// - ricker:            A (1 - 2 pi^2 f^2 tau^2) exp(-pi^2 f^2 tau^2), tau = t - t0 - 1/f,
///                                                        on [t0, t0 + 2/f] (peak A at t0 + 1/f)
/// A synthetic kind (kanai_tajimi) is generated once into a sampled record.
class MotionComponent {
 public:
  /// Builds from a scene definition (reads the file when kind is kFile). The units of an AT2
  /// file are those its header declares (g when it declares none); def.units, when given, must
  /// agree, and acceleration in other units than g is read only when def.units says which.
  /// Throws SceneError naming the file, line and what was expected.
  static MotionComponent FromDef(const MotionDef& def);
  /// kind = "kanai_tajimi": the generated record (GenerateSyntheticMotion; its peak amplitude_g
  /// when given) times scale, first sample at start_s; info().format "synthetic".
  static MotionComponent FromSynthetic(const MotionDef& def);
  /// A sampled record in m/s^2, first sample at t0_s. `resolution_mps2`, empty or one per
  /// sample (>= 0), is each sample's printed precision (see sample_resolution_mps2()).
  static MotionComponent FromSamples(std::vector<double> accel_mps2, double dt_s, double t0_s,
                                     std::string source, std::vector<double> resolution_mps2 = {});

  /// A copy with the acceleration times `factor` (records: samples and their resolution
  /// (times |factor|); analytic kinds: the amplitude); info().peak_g follows. Throws
  /// std::invalid_argument for a non-finite factor.
  MotionComponent Scaled(double factor) const;
  /// A copy of a record with other samples (m/s^2), e.g. perturbed within their resolution:
  /// same t0, dt, source, format and resolution; the peak is recomputed. Throws
  /// std::invalid_argument for an analytic kind, a different number of samples than
  /// samples_mps2() or a non-finite sample.
  MotionComponent WithSamples(std::vector<double> accel_mps2) const;

  /// Acceleration at t, m/s^2.
  double accel_mps2(double t_s) const;
  /// A record's straight piece between two consecutive sample times t_lo < t_hi, where the
  /// acceleration goes linearly from a_lo to a_hi (m/s^2). At(t) for t_lo <= t <= t_hi is
  /// accel_mps2(t), bit for bit, without its search: for callers that ask for many times in
  /// one interval (an integrator's step never crosses a sample time).
  struct LinearPiece {
    bool valid = false;
    double t_lo = 0.0, t_hi = 0.0, a_lo = 0.0, a_hi = 0.0;
    bool Holds(double t_s) const { return valid && t_s >= t_lo && t_s <= t_hi; }
    double At(double t_s) const {
      if (t_s == t_lo) return a_lo;
      if (t_s == t_hi) return a_hi;
      const double frac = (t_s - t_lo) / (t_hi - t_lo);
      return a_lo + frac * (a_hi - a_lo);
    }
  };
  /// The piece that holds t_s; not valid for analytic kinds and outside the samples.
  LinearPiece piece_at(double t_s) const;
  /// The first kink or jump strictly after t_s (a sample time, pulse start or end); +inf if none.
  double next_breakpoint_after(double t_s) const;
  /// End of the motion (last sample, pulse end; +inf for a never-ending harmonic).
  double end_s() const;
  const MotionInfo& info() const { return info_; }
  /// Appends zero samples so that the record lasts until t_end_s (records only).
  void pad_to(double t_end_s);
  /// Samples of a record (empty for analytic kinds).
  const std::vector<double>& samples_mps2() const { return samples_; }
  /// The printed precision of each sample, m/s^2: one unit of its last printed digit in the
  /// file, times the units and |scale|. Records read from files: same length as
  /// samples_mps2(), 0 for the zeros pad_to appends; FromSamples: as given (may be empty);
  /// analytic kinds: empty.
  const std::vector<double>& sample_resolution_mps2() const { return resolution_; }
  double t0_s() const { return t0_; }
  double dt_s() const { return dt_; }
  /// kFile for every sampled record (files, FromSamples, synthetic kinds); else the analytic
  /// kind, with its frequency (Hz) and the length of its window (s; +inf: an endless harmonic).
  MotionKind kind() const { return kind_; }
  double frequency_hz() const { return frequency_hz_; }
  double window_s() const { return duration_s_; }

 private:
  /// A record read (a file's, or def.samples as SampledRecord makes them) in `units`: checked
  /// against the acceleration limit, times the units and def.scale, first sample at its t0 plus
  /// def.start_s; info().format the record's.
  static MotionComponent FromRecord(const MotionDef& def, RecordData rec, AccelUnits units,
                                    std::string source);

  MotionKind kind_ = MotionKind::kFile;
  std::vector<double> samples_;     // m/s^2
  std::vector<double> resolution_;  // m/s^2, empty or one per sample
  double t0_ = 0.0, dt_ = 0.0;
  double amplitude_mps2_ = 0.0, frequency_hz_ = 0.0, duration_s_ = 0.0;
  double phase_rad_ = 0.0;  // harmonic only
  MotionInfo info_;
};

/// The base motion of a scene: optional horizontal, transverse and vertical components.
class GroundMotion {
 public:
  GroundMotion() = default;
  /// Builds the scene's components (none when the scene has no [base] table). Records of
  /// different lengths are padded with zeros to the longest (info().padded_samples says so).
  static GroundMotion FromScene(const Scene& scene);

  double xg_mps2(double t_s) const { return horizontal_ ? horizontal_->accel_mps2(t_s) : 0.0; }
  double yg_mps2(double t_s) const { return vertical_ ? vertical_->accel_mps2(t_s) : 0.0; }
  /// The transverse component (+y, a 3-D body's second horizontal direction), m/s^2.
  double transverse_mps2(double t_s) const {
    return transverse_ ? transverse_->accel_mps2(t_s) : 0.0;
  }
  /// The earliest kink of any component strictly after t_s; +inf if none.
  double next_breakpoint_after(double t_s) const;
  /// Time after which every component is zero (0 for no motion, +inf for endless harmonic).
  double end_s() const;
  bool has_horizontal() const { return horizontal_.has_value(); }
  bool has_vertical() const { return vertical_.has_value(); }
  bool has_transverse() const { return transverse_.has_value(); }
  bool empty() const { return !horizontal_ && !transverse_ && !vertical_; }
  const std::optional<MotionComponent>& horizontal() const { return horizontal_; }
  const std::optional<MotionComponent>& vertical() const { return vertical_; }
  const std::optional<MotionComponent>& transverse() const { return transverse_; }
  void set_transverse(MotionComponent c) { transverse_ = std::move(c); }
  void set_horizontal(MotionComponent c) { horizontal_ = std::move(c); }
  void set_vertical(MotionComponent c) { vertical_ = std::move(c); }

 private:
  std::optional<MotionComponent> horizontal_, transverse_, vertical_;
};

/// A record as read from a file, before units and scale.
struct RecordData {
  std::vector<double> values;      ///< acceleration in the file's units
  std::vector<double> resolution;  ///< one unit of each value's last printed digit, file units
  std::vector<int> lines;          ///< the file line of each value
  double dt_s = 0.0;
  double t0_s = 0.0;   ///< time of the first sample in the file (two-column files)
  std::string format;  ///< "AT2", "plain-2col", "plain-1col" or "samples" (SampledRecord)
  /// AT2: the acceleration units its header declares ("... IN UNITS OF G", "... CM/S/S", ...);
  /// nullopt when no header line declares units.
  std::optional<AccelUnits> header_units;
  int units_line = 0;      ///< AT2: line number of that header line (0: none)
  std::string units_text;  ///< AT2: that header line, trimmed
};

/// Reads a PEER AT2 file (all header variants of records/SOURCES.md). The header line that
/// declares the quantity and units ("ACCELERATION TIME SERIES IN UNITS OF G", "... IN UNITS OF
/// CM/S/S", "CM/SEC/SEC", "CM/S^2", "CM/S2", "GAL", "M/S/S", "M/S2"; "ACCELERATION IN CM/S/S")
/// sets header_units. Throws SceneError naming the file and line for a header that declares
/// velocity or displacement (rockbench reads acceleration) or units it does not know.
RecordData ReadAt2(const std::filesystem::path& path);
/// Reads a plain file: two columns (t, a) or one column (a, dt given by dt_s > 0), with optional
/// non-numeric header lines. Throws SceneError.
RecordData ReadPlain(const std::filesystem::path& path, double dt_s);

/// A record given by its values (MotionDef::samples, in their units) at sample interval dt_s:
/// what ParsePlain reads from a one-column file holding each value's shortest text
/// (ShortestText), the same values and the printed resolution of those texts; format "samples".
/// Throws SceneError naming `key` (".samples", ".dt") for fewer than 2 values, a non-finite one,
/// an interval outside 1e-6 to 1 s or a record longer than a day.
RecordData SampledRecord(const std::vector<double>& values, double dt_s, const std::string& key);

/// ReadAt2 and ReadPlain on a file's text already in memory; `path` names it in messages.
RecordData ParseAt2(const std::string& text, const std::filesystem::path& path);
RecordData ParsePlain(const std::string& text, const std::filesystem::path& path, double dt_s);

/// The value of one unit in the last printed digit of a decimal number token: "-.1234567E-02"
/// -> 1e-9, "0.039111" -> 1e-6, "12" -> 1, "1.5e3" -> 100 (the nearest double to 10^k). NaN
/// when the token is not a decimal number ([+-] digits [. digits] [e|E [+-] digits]).
double PrintedResolution(std::string_view token);

}  // namespace rockbench
