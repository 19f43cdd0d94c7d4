#pragma once
// A record that is zero but for one sample: the absurd base motions of the non-finite tests.
#include <utility>
#include <vector>

#include "motion/ground_motion.h"

namespace rockbench::testing_util {

constexpr double kStandardGravity_mps2 = 9.80665;  ///< m/s^2, standard gravity
constexpr double kSpikeDt_s = 0.01;                ///< s, the spike record's sample interval

/// A 2 s horizontal record (200 samples at kSpikeDt_s), zero everywhere but one sample of
/// `peak_g` (in g) at t = index * kSpikeDt_s: the acceleration ramps up from (index - 1)
/// kSpikeDt_s.
inline GroundMotion Spike(double peak_g, int index) {
  std::vector<double> a(200, 0.0);
  a[index] = peak_g * kStandardGravity_mps2;
  GroundMotion m;
  m.set_horizontal(MotionComponent::FromSamples(std::move(a), kSpikeDt_s, 0.0, "spike"));
  return m;
}

}  // namespace rockbench::testing_util
