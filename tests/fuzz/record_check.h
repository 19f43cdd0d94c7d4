#pragma once
/// What the record targets (record_at2, record_plain) do with a record that was read: what the
/// program does with it (MotionComponent::FromDef: units, the physical limit, FromSamples), then
/// what runs and studies ask of it (the acceleration at and between samples, its breakpoints,
/// its intensity measures), each checked for a finite answer.
#include <algorithm>
#include <cmath>
#include <utility>

#include "motion/ground_motion.h"
#include "motion/intensity.h"
#include "scene/limits.h"
#include "tests/fuzz/fuzz_target.h"

namespace rockbench::fuzz {

inline void CheckFinite(std::string_view target, std::string_view what, double v) {
  if (!std::isfinite(v)) {
    Finding(std::string(target) + ": " + std::string(what) + " is not finite (" + ShortestText(v) +
            ") for a record the reader accepted");
  }
}

/// `rec` in `units` (the AT2 header's, or the scene's for a plain file) as the program builds
/// it. Throws SceneError where the program does (a sample past the physical limit, a record
/// FromSamples refuses).
inline void UseRecord(std::string_view target, RecordData rec, AccelUnits units) {
  const double factor = AccelUnitsToMps2(units);
  const double max_mps2 = limits::kMaxAccel_g * kStandardGravity_mps2;
  for (double& v : rec.values) {
    v *= factor;
    // FromDef refuses a sample past the limit (with the file, line and value).
    if (!(std::abs(v) <= max_mps2)) throw SceneError("sample past the physical limit");
  }
  for (double& r : rec.resolution) r *= factor;
  const size_t n = rec.values.size();
  const MotionComponent c = MotionComponent::FromSamples(std::move(rec.values), rec.dt_s, rec.t0_s,
                                                         "fuzz", std::move(rec.resolution));
  if (c.samples_mps2().size() != n) Finding(std::string(target) + ": samples lost");
  CheckFinite(target, "peak_g", c.info().peak_g);
  CheckFinite(target, "end_s", c.end_s());
  // The acceleration at a few sample times and between them, never past the largest sample.
  const size_t step = std::max<size_t>(1, n / 16);
  for (size_t i = 0; i < n; i += step) {
    const double t = c.t0_s() + static_cast<double>(i) * c.dt_s();
    for (const double u : {t, t + 0.5 * c.dt_s()}) {
      const double a = c.accel_mps2(u);
      CheckFinite(target, "accel_mps2", a);
      if (std::abs(a) > max_mps2) Finding(std::string(target) + ": accel_mps2 past every sample");
      const MotionComponent::LinearPiece piece = c.piece_at(u);
      if (piece.Holds(u) && piece.At(u) != a) {
        Finding(std::string(target) + ": piece_at disagrees with accel_mps2");
      }
    }
    const double next = c.next_breakpoint_after(t);
    if (!(next > t)) Finding(std::string(target) + ": next_breakpoint_after does not advance");
  }
  // A study's PGA and PGV axes measure the record over the run (20 s, a typical run).
  const IntensityMeasures m = MeasureIntensity(c, 20.0);
  CheckFinite(target, "pga", m.pga_mps2);
  CheckFinite(target, "pgv", m.pgv_mps);
  CheckFinite(target, "pgd", m.pgd_m);
  CheckFinite(target, "arias", m.arias_mps);
  CheckFinite(target, "significant duration", m.significant_duration_s);
}

}  // namespace rockbench::fuzz
