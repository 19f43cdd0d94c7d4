#pragma once
/// How well the statistical verdict detects a biased engine, measured on a scene with a
/// synthetic engine: the reference model itself, with a known relative bias added to its peaks.
#include <vector>

#include "compare/verdict.h"
#include "motion/ground_motion.h"
#include "scene/scene.h"

namespace rockbench {

/// Settings of a power estimate.
struct PowerConfig {
  int reference_members = 32;  ///< the reference's perturbation members's size
  int engine_members = 16;     ///< the synthetic engine ensemble's size
  double bias = 0.05;          ///< relative bias added to every peak |theta| of the engine
  int trials = 40;             ///< independent repetitions (seeds first_seed, first_seed + 1...)
  uint64_t first_seed = 1000;
  int threads = 0;  ///< 0: every hardware thread
};

/// Rejection counts over the trials.
struct PowerEstimate {
  int trials = 0;
  int detected_biased = 0;   ///< the verdict found the biased engine inconsistent
  int flagged_unbiased = 0;  ///< the verdict found the unbiased engine inconsistent
  /// Per trial, the smallest Holm-adjusted p-value of the biased and of the unbiased engine.
  std::vector<double> min_p_biased, min_p_unbiased;
  double power() const { return trials ? static_cast<double>(detected_biased) / trials : 0.0; }
  double false_alarm_rate() const {
    return trials ? static_cast<double>(flagged_unbiased) / trials : 0.0;
  }
};

/// In trial k (seed first_seed + k) the reference's perturbation members is members 0 .. N-1 and
/// the synthetic engine ensemble is the reference model on members N .. N+M-1 (inputs drawn
/// independently of the reference sample's: the null holds exactly, so the false-alarm rate is
/// the test's size; a real engine runs on members 0 .. M-1, which only makes it more
/// conservative). The unbiased engine is that ensemble as is, the biased one multiplies its
/// peaks by 1 + bias. Both go through ComparePerturbationMembers with the scene's tolerances.
PowerEstimate EstimateVerdictPower(const Scene& scene, const GroundMotion& motion,
                                   const PowerConfig& config);

}  // namespace rockbench
