#pragma once
/// The work-precision report of a sweep folder (`rockbench sweep` output): error against wall
/// time, one curve per engine and setting family, and what it costs to reach a given agreement.
#include <filesystem>
#include <string>

#include "report/sweep/sweep_analysis.h"
#include "report/sweep/sweep_csv.h"

namespace rockbench::report {

/// Writes the report of SWEEP_DIR (it holds sweep.csv) into OUT_DIR/<report name>/: report.html,
/// report.md and figures/ (SVG plus the gnuplot script and data of each). Returns the page
/// folder. Throws std::runtime_error naming the file and line of a malformed sweep.csv.
std::filesystem::path WriteSweepReport(const std::filesystem::path& sweep_dir,
                                       const std::filesystem::path& out_dir);

/// The report's folder name under OUT_DIR: the sweep folder's own name ("sweep" when it has
/// none, e.g. "/").
std::string SweepReportName(const std::filesystem::path& sweep_dir);

}  // namespace rockbench::report
