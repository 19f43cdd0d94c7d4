#pragma once
/// The "Verdict" section of a run report, from comparison.json: per engine the verdict (agrees
/// or differs, in the run's own words) and the engines' ranking; whether the reference is converged
/// against its tighter witness; the predictability horizon of each block with the perturbation that
/// measured it; the statistical comparison of the ensembles beyond the horizon; the pointwise
/// errors split at the horizon. A folder without an ensemble (--quick, or an older rockbench) says
/// so.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "report/common/page.h"
#include "report/compare/predictability.h"

namespace rockbench::report {

struct VerdictInput {
  /// comparison.json; null in a folder without one (`rockbench run`).
  const nlohmann::json* comparison = nullptr;
  std::filesystem::path comparison_path;
  /// summary.json: its "convergence" is read when comparison.json has none.
  const nlohmann::json* summary = nullptr;
  std::filesystem::path summary_path;
  std::vector<std::string> engines;              ///< the compared engines, in page order
  int blocks = 1;                                ///< the stack's blocks
  std::optional<Predictability> predictability;  ///< nullopt: no reference ensemble was run
};

/// One engine's place in the ranking of a comparison.
struct EngineRank {
  std::string engine;
  bool agrees = false;  ///< the verdict (without one: every block within the tolerance)
  std::string kind;     ///< comparison.json verdict_kind; empty in a folder without one
  /// The earliest time at which a block leaves the comparison tolerance of the reference
  /// (comparison.json theta_i.horizon_s); the end of the comparison when none does, s.
  double agreement_horizon_s = 0.0;
  std::string first_block;  ///< "theta2", "theta5": the block that leaves first; empty: none
  /// What ranks: per block the agreement horizon capped at the reference's predictability
  /// horizon (beyond it two correct runs differ too, so a later departure ranks nothing); the
  /// earliest of the blocks, s.
  double ranked_horizon_s = 0.0;
  double compared_until_s = 0.0;      ///< s
  double wall_s = 0.0;                ///< the engine's wall time for the run, s
  double wall_per_simulated_s = 0.0;  ///< wall_s / compared_until_s (NaN: nothing compared)
};

/// The engines of `comparison` (comparison.json), in the order of `engines`, ranked: those that
/// agree first, then the later ranked horizon, then the cheaper run (wall time per simulated
/// second); ties keep the given order. Engines without an entry are left out. Throws
/// std::runtime_error naming `file` and the key when a value has the wrong type.
std::vector<EngineRank> RankEngines(const nlohmann::json& comparison,
                                    const std::vector<std::string>& engines,
                                    const std::filesystem::path& file);

/// Writes the section onto `page`. Returns the validity warnings it found (the reference not
/// converged), in plain words, for the top of the page. Throws std::runtime_error naming the
/// file and key when a value has the wrong type.
std::vector<std::string> WriteVerdictSection(const VerdictInput& in, Page& page);

}  // namespace rockbench::report
