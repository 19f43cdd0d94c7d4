#pragma once
/// The work-precision report of a sweep folder (`rockbench sweep` output): error against wall
/// time, one curve per engine and setting family, and what it costs to reach a given agreement.
#include <filesystem>

namespace rockbench::report {

/// Writes the report of SWEEP_DIR (it holds sweep.csv) into OUT_DIR/<report name>/: report.html,
/// report.md and figures/ (SVG plus the gnuplot script and data of each). Returns the page
/// folder. Throws std::runtime_error naming the file and line of a malformed sweep.csv.
std::filesystem::path WriteSweepReport(const std::filesystem::path& sweep_dir,
                                       const std::filesystem::path& out_dir);

}  // namespace rockbench::report
