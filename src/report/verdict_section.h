#pragma once
/// The "Verdict" section of a run report, from comparison.json: per engine the verdict (agrees
/// or differs, in the run's own words); whether the reference is converged against its tighter
/// witness; the predictability horizon of each block with the perturbation that measured it;
/// the statistical comparison of the ensembles beyond the horizon; the pointwise errors split at
/// the horizon. A folder without an ensemble (--quick, or an older rockbench) says so.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "report/page.h"
#include "report/predictability.h"

namespace rockbench::report {

struct VerdictInput {
  /// comparison.json; null in a folder without one (`rockbench run`).
  const nlohmann::json* comparison = nullptr;
  std::filesystem::path comparison_path;
  /// summary.json: its "convergence" is read when comparison.json has none.
  const nlohmann::json* summary = nullptr;
  std::filesystem::path summary_path;
  std::vector<std::string> engines;  ///< the compared engines, in page order
  bool two_blocks = false;
  std::optional<Predictability> predictability;  ///< nullopt: no reference ensemble was run
};

/// Writes the section onto `page`. Returns the validity warnings it found (the reference not
/// converged), in plain words, for the top of the page. Throws std::runtime_error naming the
/// file and key when a value has the wrong type.
std::vector<std::string> WriteVerdictSection(const VerdictInput& in, Page& page);

}  // namespace rockbench::report
