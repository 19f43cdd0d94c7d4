#pragma once
/// The page's Energy section: every run's energy above rest against time, evaluated from its
/// angles and rates with the reference's observables (reference/observables.h), and its
/// initial, final and largest values.
#include "reference/stack_model.h"
#include "report/run/run_figures.h"

namespace rockbench::report {

void EnergySection(const RunData& run, const reference::StackModel& model, Figures& fig);

}  // namespace rockbench::report
