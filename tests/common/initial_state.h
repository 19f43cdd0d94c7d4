#pragma once
// An initial state of one or two blocks in the order the tests write them: theta1, theta2,
// omega1, omega2 (rad, rad/s; block 2's entries 0 for one block).
#include "scene/scene.h"

namespace rockbench::testing_util {

inline InitialState Initial(double theta1_rad, double theta2_rad, double omega1_radps,
                            double omega2_radps) {
  InitialState s;
  s.theta_rad[0] = theta1_rad;
  s.theta_rad[1] = theta2_rad;
  s.omega_radps[0] = omega1_radps;
  s.omega_radps[1] = omega2_radps;
  return s;
}

}  // namespace rockbench::testing_util
