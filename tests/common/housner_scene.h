#pragma once
// Housner's block as the harness and engine tests use it: B = 1 m, H = 4 m, depth 1 m, 10 t
// (slenderness theta_c = atan(1/4)), released from rest at theta_c / 2, output every 0.01 s.
// From there the reference lands at 0.698 s and makes four impacts in 4 s.
#include <cmath>

#include "scene/scene.h"

namespace rockbench::testing_util {

inline Scene HousnerHalfAngleRelease(double duration_s) {
  Scene s;
  s.blocks = {BlockDef{1.0, 4.0, 1.0, 10000.0, 0.0}};
  s.initial.theta_rad[0] = 0.5 * std::atan(0.25);
  s.run.duration_s = duration_s;
  s.run.output_interval_s = 0.01;
  return s;
}

}  // namespace rockbench::testing_util
