#pragma once
/// The page's Impacts section: the count of each kind of event per run and the timeline of
/// impacts, mode changes and overturning, one row per run.
#include "report/run/run_figures.h"

namespace rockbench::report {

void ImpactsSection(const RunData& run, Figures& fig);

}  // namespace rockbench::report
