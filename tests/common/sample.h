#pragma once
// Samples of one or two blocks written the way the tests think of them:
// MakeSample({.t_s = 1.0, .theta1_rad = 0.1, .theta2_rad = 0.2, .mode = Mode::k1a}).
#include "scene/history.h"
#include "scene/mode.h"

namespace rockbench::testing_util {

struct SampleArgs {
  double t_s = 0.0;
  double theta1_rad = 0.0, theta2_rad = 0.0;
  double omega1_radps = 0.0, omega2_radps = 0.0;
  Mode mode = Mode::kRest;
  int blocks = 2;  ///< 1 or 2 (block 2's entries are dropped for one)
};

inline Sample MakeSample(const SampleArgs& a) {
  Sample s(a.blocks);
  s.t_s = a.t_s;
  s.theta_rad[0] = a.theta1_rad;
  s.omega_radps[0] = a.omega1_radps;
  if (a.blocks == 2) {
    s.theta_rad[1] = a.theta2_rad;
    s.omega_radps[1] = a.omega2_radps;
  }
  s.mode = ConfigurationOf(a.mode, a.blocks);
  return s;
}

}  // namespace rockbench::testing_util
