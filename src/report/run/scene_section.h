#pragma once
/// The page's Scene section: the blocks, the initial state and run settings, the base motion
/// (PGA, PGV, PGD and a plot of the record) and every engine's settings.
#include "motion/ground_motion.h"
#include "report/run/run_figures.h"

namespace rockbench::report {

void SceneSection(const RunData& run, const GroundMotion& motion, Figures& fig);

}  // namespace rockbench::report
