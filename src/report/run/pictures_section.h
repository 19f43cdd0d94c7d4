#pragma once
/// The page's Keyframes and Animation: frames drawn from the histories (renders/) at the peaks,
/// overturning and the reference's first impacts, and the animation of the whole run.
#include "report/run/run_figures.h"
#include "report/run/run_report.h"
#include "scene/ground_motion.h"

namespace rockbench::report {

void PicturesSection(const RunData& run, const GroundMotion& motion,
                     const RunReportOptions& options, Figures& fig, RunReportResult& result);

}  // namespace rockbench::report
