#pragma once
/// The report of an ensemble folder (`rockbench ensemble` output: study.json, members.csv):
/// the study and its runs' statuses, the overturning spectra of a pulse study, the fragility
/// curves of a motion-suite study, peak angle against PGA, and the study's result in plain
/// words. See docs/ensemble.md.
#include <filesystem>

namespace rockbench::report {

/// Writes OUT_DIR/<folder name>/report.html, report.md and figures/. Returns the page folder.
/// Throws ReportInputError naming the file and line of a malformed study.json or members.csv.
std::filesystem::path WriteEnsembleReport(const std::filesystem::path& ensemble_dir,
                                          const std::filesystem::path& out_dir);

}  // namespace rockbench::report
