#pragma once
// An analytic base motion as a scene's [base.horizontal] table would give it, for tests.
#include <limits>

#include "scene/scene.h"

namespace rockbench::testing_util {

/// kind with amplitude A (g), frequency f (Hz; unused by the rectangular pulse), start t0 (s)
/// and duration (s; +inf: a harmonic that never stops).
inline MotionDef AnalyticMotion(MotionKind kind, double amplitude_g, double f_hz, double t0_s,
                                double duration_s = std::numeric_limits<double>::infinity()) {
  MotionDef d;
  d.key = "base.horizontal";
  d.kind = kind;
  d.amplitude_g = amplitude_g;
  d.frequency_hz = f_hz;
  d.start_s = t0_s;
  d.duration_s = duration_s;
  return d;
}

}  // namespace rockbench::testing_util
