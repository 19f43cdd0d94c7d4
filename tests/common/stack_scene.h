#pragma once
// A stack of N blocks (issue 23) built in code for the tests of what comes after a history
// (compare, report, study, sweep): drums narrowing upwards (block k, k = 1..N: width 1 - 0.06 (k
// - 1) m, height 2 - 0.1 (k - 1) m, 2500 kg/m^3, depth 1 m; each no wider than the one below),
// output every 0.01 s, run by the reference on the pivot chain (docs/n-blocks.md).
// Initial state: theta_k = 0.02 + step (k - 1) rad. Three blocks (step 0.004) rock with every
// interface open on its right corner from the start and complete 1.5 s. More (step 0): a taller
// stack released with its interfaces open whips its top until a pivot would pull (the model
// stops, assumption_violated, within 0.3 s), so it is released as one column, every block at
// 0.02 rad, and rocks locked (one ground impact in 1.5 s).
#include <string>

#include "scene/scene.h"

namespace rockbench::testing_util {

/// Two blocks (full widths and heights, m; masses, kg), block 2 on block 1, and nothing else
/// set: the stack of the tests that place or draw blocks without running them.
inline Scene TwoBlockScene(double width1_m, double height1_m, double mass1_kg, double width2_m,
                           double height2_m, double mass2_kg) {
  Scene s;
  s.blocks = {BlockDef{.width_m = width1_m, .height_m = height1_m, .mass_kg = mass1_kg},
              BlockDef{.width_m = width2_m, .height_m = height2_m, .mass_kg = mass2_kg}};
  return s;
}

inline double StackTiltStep(int blocks) {
  return blocks <= 3 ? 0.004 : 0.0;
}

inline Scene StackScene(int blocks, double duration_s) {
  Scene s;
  for (int k = 0; k < blocks; ++k) {
    const double B = 1.0 - 0.06 * k, H = 2.0 - 0.1 * k;
    s.blocks.push_back(BlockDef{B, H, 1.0, 2500.0 * B * H, 2500.0});
    s.initial.theta_rad[k] = 0.02 + StackTiltStep(blocks) * k;
  }
  s.run.duration_s = duration_s;
  s.run.output_interval_s = 0.01;
  return s;
}

/// The same stack as a scene file's text ([[block]] tables).
inline std::string StackSceneToml(int blocks, double duration_s) {
  std::string t = "title = \"a stack of " + std::to_string(blocks) + " drums\"\n";
  std::string theta;
  for (int k = 0; k < blocks; ++k) {
    const double B = 1.0 - 0.06 * k, H = 2.0 - 0.1 * k;
    t += "[[block]]\nwidth = " + std::to_string(B) + "\nheight = " + std::to_string(H) +
         "\ndensity = 2500.0\n";
    theta += (k == 0 ? "" : ", ") + std::to_string(0.02 + StackTiltStep(blocks) * k);
  }
  t += "[initial]\ntheta = [" + theta + "]\n[run]\nduration = " + std::to_string(duration_s) +
       "\noutput_interval = 0.01\n";
  return t;
}

}  // namespace rockbench::testing_util
