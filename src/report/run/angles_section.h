#pragma once
/// The page's Angles figure: theta1 and theta2 of the reference and every engine on shared
/// axes, the reference ensemble's band behind, overturning and predictability marks.
#include "report/run/run_figures.h"

namespace rockbench::report {

void AnglesFigure(const RunData& run, Figures& fig);

}  // namespace rockbench::report
