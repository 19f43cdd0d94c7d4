#pragma once
/// The reference ensemble as a report reads it from a `rockbench compare` folder:
/// comparison.json "predictability" (members, their perturbation, the predictability horizon of
/// each block) and reference/ensemble_band.csv (the band every member and the nominal run span).
/// A folder made with --quick, or by a rockbench older than the ensembles, has neither.
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rockbench::report {

/// comparison.json "predictability".
struct Predictability {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int members = 0;
  /// The perturbation of member inputs (NaN when not recorded): base-motion amplitude factor
  /// 1 + u amplitude_rel, each record sample moved by u sample_precision units of its last printed
  /// digit, each nonzero initial value factor 1 + u initial_rel, u uniform in [-1, 1]; the seed.
  double amplitude_rel = kNaN, sample_precision = kNaN, initial_rel = kNaN, seed = kNaN;
  std::string rule;  ///< the perturbation rule in words, as recorded
  /// Per block (theta1, theta2, ..., block k at k - 1): the first time a member leaves the
  /// nominal run by more than the comparison tolerance; nullopt: every member stays within it
  /// (predictable for the whole run). One entry per block, at least two (one block's second:
  /// nullopt and NaN).
  std::vector<std::optional<double>> horizon_s = std::vector<std::optional<double>>(2);
  std::vector<double> tolerance_rad = {kNaN, kNaN};   ///< the comparison tolerance per block
  std::vector<double> spread_rad = {kNaN, kNaN};      ///< largest |member - nominal| over the run
  std::vector<std::pair<std::string, int>> statuses;  ///< members per outcome ("overturned", ...)
  double wall_s = kNaN;                               ///< wall time of the whole ensemble
};

/// The "predictability" of comparison.json (`file` for messages); nullopt when no ensemble was
/// run: the key absent (an older rockbench), null or with no members (--quick). Throws
/// std::runtime_error naming the file and key when a value has the wrong type. `blocks`: the
/// stack's blocks (theta1 .. thetaN are read).
std::optional<Predictability> ReadPredictability(const nlohmann::json& comparison,
                                                 const std::filesystem::path& file, int blocks);
/// (A bool here was "two blocks": give the number of blocks.)
std::optional<Predictability> ReadPredictability(const nlohmann::json&,
                                                 const std::filesystem::path&, bool) = delete;

/// reference/ensemble_band.csv on the output grid, rad.
struct EnsembleBand {
  int blocks = 1;  ///< the blocks of the file's columns
  std::vector<double> t_s;
  /// Per block (block k at k - 1), one entry per block, at least two (one block's second
  /// empty):
  std::vector<std::vector<double>> lo_rad = std::vector<std::vector<double>>(2),
                                   hi_rad = std::vector<std::vector<double>>(2);  ///< the band
  /// The largest |member - nominal| at each time.
  std::vector<std::vector<double>> spread_rad = std::vector<std::vector<double>>(2);
};

/// Reads t,theta1_lo,theta1_hi,theta1_spread[,theta2_lo,theta2_hi,theta2_spread[,...,
/// thetaN_spread]] (every block whose thetaK_lo column is there, K = 1, 2, ... in turn), or a
/// cylinder's t,tilt1_lo,tilt1_hi,tilt1_spread (its tilt's band, its tilt vector's spread);
/// nullopt when the file does not exist. Throws std::runtime_error naming the file (and line)
/// when it is malformed.
std::optional<EnsembleBand> ReadEnsembleBand(const std::filesystem::path& csv);

}  // namespace rockbench::report
