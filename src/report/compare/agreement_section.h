#pragma once
/// The page's Agreement section: the metrics table of comparison.json and the angle error of
/// every engine against the reference (interpolated between its samples), with the tolerance,
/// the agreement horizons and the reference ensemble's spread and predictability horizon.
#include "report/run/run_figures.h"
#include "report/run/run_report.h"

namespace rockbench::report {

void AgreementSection(const RunData& run, const RunReportOptions& options, Figures& fig);

}  // namespace rockbench::report
