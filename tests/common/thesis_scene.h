#pragma once
// The thesis's free-rocking stack (section 6.3.1) as the reference tests use it: B1 = H1 =
// 1.25 m, B2 = 1.0 m, H2 = 2.5 m, depth 1 m, 2500 kg/m^3, both blocks released together from
// 0.15 rad, no ground motion.
#include "scene/scene.h"

namespace rockbench::testing_util {

inline Scene ThesisFreeRockingStack(double duration_s = 6.0, double output_interval_s = 0.005) {
  Scene sc;
  sc.blocks = {BlockDef{1.25, 1.25, 1.0, 3906.25, 2500.0}, BlockDef{1.0, 2.5, 1.0, 6250.0, 2500.0}};
  sc.initial.theta_rad[0] = sc.initial.theta_rad[1] = 0.15;
  sc.run.duration_s = duration_s;
  sc.run.output_interval_s = output_interval_s;
  return sc;
}

}  // namespace rockbench::testing_util
