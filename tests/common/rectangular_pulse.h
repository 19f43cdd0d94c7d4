#pragma once
// Whether a rectangular pulse of amplitude_g (in units of the scene's gravity) lasting
// duration_s overturns the scene's block, run by the reference with `equations`. The run must
// stay within the model's assumptions (no uplift, nothing non-finite): it ends overturned,
// completed or at rest with no status detail, else the calling test fails. Shared by
// tests/reference/pulse_test.cc, closed_forms_test.cc and unilateral_test.cc.
#include <gtest/gtest.h>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// A horizontal rectangular pulse of amplitude_g (g) from start_s for duration_s.
inline MotionDef RectangularPulseDef(double amplitude_g, double duration_s, double start_s = 0.0) {
  MotionDef d;
  d.key = "base.horizontal";
  d.kind = MotionKind::kRectangularPulse;
  d.amplitude_g = amplitude_g;
  d.duration_s = duration_s;
  d.start_s = start_s;
  return d;
}

inline bool RectangularPulseOverturns(Scene s, double amplitude_g, double duration_s,
                                      Equations equations) {
  s.model.equations = equations;
  s.horizontal = RectangularPulseDef(amplitude_g, duration_s);
  const Summary sum = Simulate(s, GroundMotion::FromScene(s)).summary;
  EXPECT_TRUE(sum.status == RunStatus::kOverturned || sum.status == RunStatus::kCompleted ||
              sum.status == RunStatus::kAtRest)
      << sum.status << " at " << amplitude_g << " g";
  EXPECT_EQ(sum.status_detail, "") << amplitude_g << " g";
  return sum.status == RunStatus::kOverturned;
}

}  // namespace rockbench::reference
