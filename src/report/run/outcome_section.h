#pragma once
/// The page's Outcome: the reference's status and each engine's in one line, the validity
/// warnings of their summaries (assumptions violated, inadmissible impacts, energy gain;
/// engines' sliding, uplift, penetration, energy growth, blow-up), and the Verdict section.
#include <string>
#include <vector>

#include "report/common/page.h"
#include "report/run/run_readers.h"
#include "report/run/run_report.h"

namespace rockbench::report {

/// The reference's outcome when it stopped because an assumption was violated (status
/// "assumption_violated", a planar stack's or a cylinder's), in words; appends the warning
/// naming when (its events) and why (status_detail).
std::string AssumptionViolatedOutcome(const RunData& run, std::vector<std::string>& warnings);

/// The reference's outcome in words; appends the warnings of its summary.
std::string ReferenceOutcome(const RunData& run, std::vector<std::string>& warnings);

/// The engines' outcomes in words (" Engines compared: ...", or that none was); appends the
/// warnings of each engine's summary.
std::string EnginesOutcome(const RunData& run, std::vector<std::string>& warnings);

/// The Verdict section (verdict_section.h) of the run; appends its warnings to result.
void VerdictSection(const RunData& run, Page& page, RunReportResult& result);

}  // namespace rockbench::report
