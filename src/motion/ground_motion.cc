#include "motion/ground_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "motion/synthetic_motion.h"
#include "scene/limits.h"

namespace rockbench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

// Length of an analytic kind's active window [t0, t0 + length].
double AnalyticLength(const MotionDef& def) {
  switch (def.kind) {
    case MotionKind::kHarmonic:
      return def.duration_s;
    case MotionKind::kSinePulse:
    case MotionKind::kCosinePulse:
      return 1.0 / def.frequency_hz;
    case MotionKind::kRectangularPulse:
      return def.duration_s;
    case MotionKind::kRicker:
      return 2.0 / def.frequency_hz;
    case MotionKind::kFile:
    case MotionKind::kKanaiTajimi:
      break;
  }
  return 0.0;
}

// Fills the peak of a sampled record (first largest |a|), in standard g.
void SamplePeak(const std::vector<double>& a, double t0, double dt, MotionInfo& info) {
  double peak = 0.0;
  size_t at = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i]) > peak) {
      peak = std::abs(a[i]);
      at = i;
    }
  }
  info.peak_g = peak / kStandardGravity_mps2;
  info.peak_t_s = t0 + static_cast<double>(at) * dt;
}

}  // namespace

MotionComponent MotionComponent::FromSamples(std::vector<double> accel_mps2, double dt_s,
                                             double t0_s, std::string source,
                                             std::vector<double> resolution_mps2) {
  if (accel_mps2.empty()) throw SceneError(source + ": a record needs at least one sample");
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw SceneError(source + ": expected a positive finite sample interval (s)");
  }
  if (!std::isfinite(t0_s)) throw SceneError(source + ": expected a finite start time (s)");
  for (size_t i = 0; i < accel_mps2.size(); ++i) {
    if (!std::isfinite(accel_mps2[i])) {
      throw SceneError(source + ": sample " + std::to_string(i) + " is not finite");
    }
  }
  if (!resolution_mps2.empty() && resolution_mps2.size() != accel_mps2.size()) {
    throw SceneError(source + ": expected one resolution per sample (" +
                     std::to_string(accel_mps2.size()) + "), got " +
                     std::to_string(resolution_mps2.size()));
  }
  for (size_t i = 0; i < resolution_mps2.size(); ++i) {
    if (!(resolution_mps2[i] >= 0.0) || !std::isfinite(resolution_mps2[i])) {
      throw SceneError(source + ": the resolution of sample " + std::to_string(i) +
                       " must be finite and >= 0 (m/s^2)");
    }
  }
  MotionComponent c;
  c.kind_ = MotionKind::kFile;
  c.samples_ = std::move(accel_mps2);
  c.resolution_ = std::move(resolution_mps2);
  c.t0_ = t0_s;
  c.dt_ = dt_s;
  c.info_.source = std::move(source);
  c.info_.format = "samples";
  c.info_.npts = static_cast<int>(c.samples_.size());
  c.info_.dt_s = dt_s;
  c.info_.duration_s = static_cast<double>(c.samples_.size() - 1) * dt_s;
  SamplePeak(c.samples_, t0_s, dt_s, c.info_);
  return c;
}

MotionComponent MotionComponent::FromSynthetic(const MotionDef& def) {
  const SyntheticMotionDef d = def.SyntheticProcess();
  std::vector<double> a;
  try {
    a = GenerateSyntheticMotion(d);
  } catch (const std::invalid_argument& e) {
    throw SceneError(def.key + ": " + e.what());
  }
  // The generated peak after scale, within the physical limit (an intensity too large for the
  // limit names its key).
  const double max_mps2 = limits::kMaxAccel_g * kStandardGravity_mps2;
  for (double& v : a) {
    v *= def.scale;
    if (!(std::abs(v) <= max_mps2)) {
      const std::string key = def.amplitude_g > 0.0 ? def.key + ".scale" : def.key + ".intensity";
      char peak[32];
      std::snprintf(peak, sizeof peak, "%.6g", std::abs(v) / kStandardGravity_mps2);
      throw SceneError(key + ": the generated record reaches " + std::string(peak) +
                       " g; expected an acceleration with magnitude at most " +
                       ShortestText(limits::kMaxAccel_g) + " g (docs/limits.md)");
    }
  }
  MotionComponent c = FromSamples(std::move(a), d.dt_s, def.start_s,
                                  "kanai_tajimi (seed " + std::to_string(d.seed) + ")");
  c.info_.format = "synthetic";
  return c;
}

MotionComponent MotionComponent::FromRecord(const MotionDef& def, RecordData rec, AccelUnits units,
                                            std::string source) {
  // Every sample within the physical limit, after units and scale (scene/limits.h): a file's
  // named by its file, line and number, samples' by their key and index.
  for (size_t i = 0; i < rec.values.size(); ++i) {
    const std::string problem = SampleAccelProblem(def, units, rec.values[i]);
    if (problem.empty()) continue;
    if (def.from_samples()) {
      throw SceneError(def.key + ".samples[" + std::to_string(i) + "]" + problem);
    }
    std::string line;
    if (i < rec.lines.size()) line.append(":").append(std::to_string(rec.lines[i]));
    throw SceneError(def.file.string() + line + ": sample " + std::to_string(i + 1) + problem);
  }
  const double factor = AccelUnitsToMps2(units) * def.scale;
  for (double& v : rec.values) v *= factor;
  for (double& r : rec.resolution) r *= std::abs(factor);
  MotionComponent c = FromSamples(std::move(rec.values), rec.dt_s, rec.t0_s + def.start_s,
                                  std::move(source), std::move(rec.resolution));
  c.info_.format = rec.format;
  return c;
}

MotionComponent MotionComponent::FromDef(const MotionDef& def) {
  if (def.kind == MotionKind::kFile && !def.samples.empty()) {
    if (!def.file.empty()) {
      throw SceneError(def.key +
                       ": give one of file, kind or samples, not several (file and "
                       "samples)");
    }
    if (!def.units_given) {
      throw SceneError(def.key +
                       ".units: samples must state their units: \"g\", \"m/s2\" or "
                       "\"cm/s2\"");
    }
    RecordData rec = SampledRecord(def.samples, def.dt_s, def.key);
    // A stated resolution replaces the one of the samples' shortest texts.
    if (def.samples_resolution) {
      if (!(*def.samples_resolution >= 0.0) || !std::isfinite(*def.samples_resolution)) {
        throw SceneError(def.key +
                         ".resolution: expected a number >= 0 (in the samples' units), got " +
                         ShortestText(*def.samples_resolution));
      }
      rec.resolution.assign(rec.values.size(), *def.samples_resolution);
    }
    const std::string source = "samples (" + std::to_string(def.samples.size()) + " values)";
    return FromRecord(def, std::move(rec), def.units, source);
  }
  if (def.kind != MotionKind::kFile && !def.samples.empty()) {
    throw SceneError(def.key + ": give one of file, kind or samples, not several (kind = \"" +
                     std::string(MotionKindName(def.kind)) + "\" and samples)");
  }
  if (def.kind == MotionKind::kFile) {
    const bool at2 = IsAt2File(def.file);
    RecordData rec = at2 ? ReadAt2(def.file) : ReadPlain(def.file, def.dt_s);
    AccelUnits units = AccelUnits::kG;  // an AT2 file whose header declares no units: PEER's g
    const auto name = [](AccelUnits u) { return "\"" + std::string(AccelUnitsName(u)) + "\""; };
    if (at2 && rec.header_units) {
      const AccelUnits header = *rec.header_units;
      const std::string where = def.file.string() + ":" + std::to_string(rec.units_line) + ": ";
      const std::string says = "the AT2 header says \"" + rec.units_text + "\" (" +
                               std::string(AccelUnitsName(header)) + ")";
      if (def.units_given && def.units != header) {
        throw SceneError(where + def.key + ".units is " + name(def.units) + " but " + says +
                         (header == AccelUnits::kG ? ": omit units or use \"g\""
                                                   : ": use units = " + name(header)));
      }
      if (!def.units_given && header != AccelUnits::kG) {
        // Read only when the scene says so: a file in g is the norm, and a header misread as
        // another unit would go unnoticed.
        throw SceneError(where + says + ", not g: set " + def.key + ".units = " + name(header) +
                         " to read it in those units");
      }
      units = header;
    } else if (def.units_given) {
      units = def.units;
    } else if (!at2) {
      throw SceneError(def.file.string() + ": " + def.key +
                       ".units: a plain record file must state its units: \"g\", \"m/s2\" or "
                       "\"cm/s2\"");
    }
    std::string source = def.file_as_written.empty() ? def.file.string() : def.file_as_written;
    return FromRecord(def, std::move(rec), units, std::move(source));
  }
  if (def.kind == MotionKind::kKanaiTajimi) return FromSynthetic(def);
  MotionComponent c;
  c.kind_ = def.kind;
  c.t0_ = def.start_s;
  c.amplitude_mps2_ = def.amplitude_g * kStandardGravity_mps2 * def.scale;
  c.frequency_hz_ = def.frequency_hz;
  c.phase_rad_ = def.phase_deg * (kPi / 180.0);
  c.duration_s_ = AnalyticLength(def);
  c.info_.source = std::string(MotionKindName(def.kind));
  c.info_.format = "analytic";
  c.info_.duration_s = c.duration_s_;
  // Exact peak of each shape: |A| where the shape reaches 1, unless a harmonic stops earlier.
  const double amp_g = std::abs(def.amplitude_g * def.scale);
  switch (def.kind) {
    case MotionKind::kHarmonic: {
      // The first crest: where the phase 2 pi f tau + phase first reaches pi/2 modulo pi.
      const double w = 2.0 * kPi * def.frequency_hz;
      const double crest = std::fmod(std::fmod(0.5 * kPi - c.phase_rad_, kPi) + kPi, kPi) / w;
      if (c.duration_s_ >= crest) {
        c.info_.peak_g = amp_g;
        c.info_.peak_t_s = c.t0_ + crest;
      } else {
        // No crest inside: |sin| is largest at an end of the window.
        const double at_start = std::abs(std::sin(c.phase_rad_));
        const double at_end = std::abs(std::sin(w * c.duration_s_ + c.phase_rad_));
        c.info_.peak_g = amp_g * std::max(at_start, at_end);
        c.info_.peak_t_s = c.t0_ + (at_end > at_start ? c.duration_s_ : 0.0);
      }
      break;
    }
    case MotionKind::kSinePulse:
      c.info_.peak_g = amp_g;
      c.info_.peak_t_s = c.t0_ + 0.25 / def.frequency_hz;
      break;
    case MotionKind::kCosinePulse:
    case MotionKind::kRectangularPulse:
      c.info_.peak_g = amp_g;
      c.info_.peak_t_s = c.t0_;
      break;
    case MotionKind::kRicker:
      // The central lobe (shape 1 at tau = 0) exceeds the side lobes (2 exp(-3/2) = 0.446).
      c.info_.peak_g = amp_g;
      c.info_.peak_t_s = c.t0_ + 1.0 / def.frequency_hz;
      break;
    case MotionKind::kFile:
    case MotionKind::kKanaiTajimi:  // sampled records (FromDef, FromSynthetic)
      break;
  }
  return c;
}

double MotionComponent::accel_mps2(double t_s) const {
  if (kind_ == MotionKind::kFile) {
    const size_t n = samples_.size();
    if (n == 0) return 0.0;
    const auto sample_t = [&](size_t i) { return t0_ + static_cast<double>(i) * dt_; };
    // Zero before the first sample and after the last (false for NaN too).
    if (!(t_s >= t0_ && t_s <= sample_t(n - 1))) return 0.0;
    size_t i =
        static_cast<size_t>(std::min(std::floor((t_s - t0_) / dt_), static_cast<double>(n - 1)));
    // Index arithmetic may be one off in floating point; settle on sample_t(i) <= t < next.
    while (i + 1 < n && sample_t(i + 1) <= t_s) ++i;
    while (i > 0 && sample_t(i) > t_s) --i;
    const double ti = sample_t(i);
    if (ti == t_s || i + 1 == n) return samples_[i];
    const double frac = (t_s - ti) / (sample_t(i + 1) - ti);
    return samples_[i] + frac * (samples_[i + 1] - samples_[i]);
  }
  const double end = t0_ + duration_s_;
  if (!(t_s >= t0_ && t_s <= end)) return 0.0;
  const double tau = t_s - t0_;
  const double w = 2.0 * kPi * frequency_hz_;
  switch (kind_) {
    case MotionKind::kHarmonic:
      return amplitude_mps2_ * std::sin(w * tau + phase_rad_);
    case MotionKind::kSinePulse:
      return amplitude_mps2_ * std::sin(w * tau);
    case MotionKind::kCosinePulse:
      return amplitude_mps2_ * std::cos(w * tau);
    case MotionKind::kRectangularPulse:
      return amplitude_mps2_;
    case MotionKind::kRicker: {
      const double x = kPi * frequency_hz_ * (tau - 1.0 / frequency_hz_);
      return amplitude_mps2_ * (1.0 - 2.0 * x * x) * std::exp(-x * x);
    }
    case MotionKind::kFile:
    case MotionKind::kKanaiTajimi:  // sampled: kind_ is kFile
      break;
  }
  return 0.0;
}

MotionComponent::LinearPiece MotionComponent::piece_at(double t_s) const {
  LinearPiece piece;
  const size_t n = samples_.size();
  if (kind_ != MotionKind::kFile || n < 2) return piece;
  const auto sample_t = [&](size_t i) { return t0_ + static_cast<double>(i) * dt_; };
  if (!(t_s >= t0_ && t_s <= sample_t(n - 1))) return piece;
  // The index as accel_mps2 finds it, kept below the last sample.
  size_t i =
      static_cast<size_t>(std::min(std::floor((t_s - t0_) / dt_), static_cast<double>(n - 2)));
  while (i + 2 < n && sample_t(i + 1) <= t_s) ++i;
  while (i > 0 && sample_t(i) > t_s) --i;
  piece.valid = true;
  piece.t_lo = sample_t(i);
  piece.t_hi = sample_t(i + 1);
  piece.a_lo = samples_[i];
  piece.a_hi = samples_[i + 1];
  return piece;
}

double MotionComponent::next_breakpoint_after(double t_s) const {
  if (kind_ == MotionKind::kFile) {
    const size_t n = samples_.size();
    if (n == 0) return kInf;
    const auto sample_t = [&](size_t i) { return t0_ + static_cast<double>(i) * dt_; };
    if (t_s < t0_) return t0_;
    if (!(t_s < sample_t(n - 1))) return kInf;
    // O(1): the index from arithmetic, then at most a step either way for rounding.
    size_t i = static_cast<size_t>(
        std::min(std::floor((t_s - t0_) / dt_) + 1.0, static_cast<double>(n - 1)));
    while (i > 0 && sample_t(i - 1) > t_s) --i;
    while (i + 1 < n && sample_t(i) <= t_s) ++i;
    return sample_t(i);
  }
  if (t_s < t0_) return t0_;
  const double end = t0_ + duration_s_;
  if (t_s < end) return end;  // +inf for a never-ending harmonic
  return kInf;
}

double MotionComponent::end_s() const {
  if (kind_ == MotionKind::kFile) {
    if (samples_.empty()) return 0.0;
    return t0_ + static_cast<double>(samples_.size() - 1) * dt_;
  }
  return t0_ + duration_s_;
}

void MotionComponent::pad_to(double t_end_s) {
  if (kind_ != MotionKind::kFile || samples_.empty() || !std::isfinite(t_end_s)) return;
  if (t_end_s <= end_s()) return;
  // Samples needed so that the last one is at or after t_end (1e-9 of dt absorbs rounding).
  const double last_index = std::ceil((t_end_s - t0_) / dt_ - 1e-9);
  const size_t n_new = static_cast<size_t>(last_index) + 1;
  if (n_new <= samples_.size()) return;
  info_.padded_samples += static_cast<int>(n_new - samples_.size());
  samples_.resize(n_new, 0.0);
  // The appended zeros are exact.
  if (!resolution_.empty()) resolution_.resize(n_new, 0.0);
}

MotionComponent MotionComponent::Scaled(double factor) const {
  if (!std::isfinite(factor)) {
    throw std::invalid_argument(info_.source + ": Scaled: expected a finite factor, got " +
                                std::to_string(factor));
  }
  MotionComponent c = *this;
  if (kind_ == MotionKind::kFile) {
    for (double& v : c.samples_) v *= factor;
    for (double& r : c.resolution_) r *= std::abs(factor);
    SamplePeak(c.samples_, c.t0_, c.dt_, c.info_);
  } else {
    c.amplitude_mps2_ *= factor;
    c.info_.peak_g *= std::abs(factor);
  }
  return c;
}

MotionComponent MotionComponent::WithSamples(std::vector<double> accel_mps2) const {
  if (kind_ != MotionKind::kFile) {
    throw std::invalid_argument(info_.source + ": WithSamples: an analytic motion has no samples");
  }
  if (accel_mps2.size() != samples_.size()) {
    throw std::invalid_argument(info_.source + ": WithSamples: expected " +
                                std::to_string(samples_.size()) + " samples, got " +
                                std::to_string(accel_mps2.size()));
  }
  for (size_t i = 0; i < accel_mps2.size(); ++i) {
    if (!std::isfinite(accel_mps2[i])) {
      throw std::invalid_argument(info_.source + ": WithSamples: sample " + std::to_string(i) +
                                  " is not finite");
    }
  }
  MotionComponent c = *this;
  c.samples_ = std::move(accel_mps2);
  SamplePeak(c.samples_, c.t0_, c.dt_, c.info_);
  return c;
}

GroundMotion GroundMotion::FromScene(const Scene& scene) {
  GroundMotion g;
  // A synthetic motion's errors start with its key: the scene file goes before it.
  const auto build = [&](const MotionDef& def) {
    try {
      return MotionComponent::FromDef(def);
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      if (!scene.path.empty() && msg.rfind(def.key, 0) == 0) {
        std::string where = Excerpt(scene.path.string(), 200);
        where.append(": ").append(msg);
        throw SceneError(where);
      }
      throw;
    }
  };
  if (scene.horizontal) g.horizontal_ = build(*scene.horizontal);
  if (scene.transverse) g.transverse_ = build(*scene.transverse);
  if (scene.vertical) g.vertical_ = build(*scene.vertical);
  // Records of different lengths: the shorter ones get zeros at their end.
  std::vector<MotionComponent*> records;
  for (std::optional<MotionComponent>* c : {&g.horizontal_, &g.transverse_, &g.vertical_}) {
    if (*c && !(*c)->samples_mps2().empty()) records.push_back(&**c);
  }
  if (records.size() >= 2) {
    double end = 0.0;
    for (const MotionComponent* c : records) end = std::max(end, c->end_s());
    for (MotionComponent* c : records) c->pad_to(end);
  }
  return g;
}

double GroundMotion::next_breakpoint_after(double t_s) const {
  double next = kInf;
  if (horizontal_) next = std::min(next, horizontal_->next_breakpoint_after(t_s));
  if (transverse_) next = std::min(next, transverse_->next_breakpoint_after(t_s));
  if (vertical_) next = std::min(next, vertical_->next_breakpoint_after(t_s));
  return next;
}

double GroundMotion::end_s() const {
  double end = 0.0;
  if (horizontal_) end = std::max(end, horizontal_->end_s());
  if (transverse_) end = std::max(end, transverse_->end_s());
  if (vertical_) end = std::max(end, vertical_->end_s());
  return end;
}

}  // namespace rockbench
