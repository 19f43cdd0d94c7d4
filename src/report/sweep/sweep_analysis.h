#pragma once
/// The work-precision analysis of a sweep's records: agreement criteria, the cheapest setting of
/// an engine reaching one and the reference setting that beats it, families and observed orders.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "report/sweep/sweep_csv.h"

namespace rockbench::report {

/// The 1% criterion: |peak_rel_error| <= peak_tolerance for theta1 and theta2, and the same
/// overturn outcome as the reference. Failed rows never qualify.
bool ReachesPeakAgreement(const SweepRecord& r, double peak_tolerance);

/// An agreement criterion: a run reaches it or not.
struct AgreementCriterion {
  std::string name;        ///< short, e.g. "1% peak-angle agreement"
  std::string definition;  ///< in words, for the statement
  /// Whether a row reaches it (failed rows never do, whatever this says).
  std::function<bool(const SweepRecord&)> reaches;
};

/// The criterion: ReachesPeakAgreement(r, tolerance). `blocks`: the stack's blocks, which
/// the definition names (theta1; theta1 and theta2; every block, theta1 to thetaN).
AgreementCriterion PeakAgreement(double tolerance, int blocks);
/// A stricter one on the whole history: max |theta_k error| over the run <= fraction x the
/// reference's peak |theta_k| for each body k (`peak_theta_rad`, rad, body k at k - 1; a body
/// after the first with a peak of 0, such as one block's body 2 in sweep.json, has no bound),
/// and the same overturn outcome.
AgreementCriterion HistoryAgreement(double fraction, const std::vector<double>& peak_theta_rad);

/// The cheapest setting of one engine reaching a criterion, and the cheapest reference setting
/// with the same or better accuracy: max angle error <= the engine run's, and it reaches the
/// criterion too. Indices into the rows; ties go to the earlier row.
struct CheapestSetting {
  std::string engine;  ///< the engine
  std::optional<size_t> engine_row;
  std::optional<size_t> reference;
  /// The statement in plain words (says so when no engine or no reference setting qualifies).
  std::string statement;
};
/// `engine`: empty for the first engine of the rows.
CheapestSetting FindCheapestSetting(const std::vector<SweepRecord>& rows,
                                    const AgreementCriterion& criterion,
                                    const std::string& engine = "");
/// With PeakAgreement(peak_tolerance, the most bodies of a row).
CheapestSetting FindCheapestSetting(const std::vector<SweepRecord>& rows,
                                    double peak_tolerance = 0.01, const std::string& engine = "");
/// The engines of the rows, in the order they first appear.
std::vector<std::string> SweepEngines(const std::vector<SweepRecord>& rows);

/// Rows grouped by family, in the order the engines' families first appear, then reference
/// dopri5, reference RK4; within a family from the coarsest setting to the finest.
/// Failed rows are left out. (family name, row indices).
std::vector<std::pair<std::string, std::vector<size_t>>> SweepFamilies(
    const std::vector<SweepRecord>& rows);

/// Observed order of convergence between two rows of a family (coarse, fine):
/// log(e_coarse / e_fine) / log(s_coarse / s_fine) with e the max angle error and s the setting
/// value; empty when an error is zero or the settings are equal.
std::optional<double> ObservedOrder(const SweepRecord& coarse, const SweepRecord& fine);

/// An engine's fitted order of convergence: the least-squares slope of log(max angle error)
/// against log(setting) over the rows of one family (zero errors left out); empty with fewer
/// than two usable rows.
struct FittedOrder {
  std::string family;
  double order = 0.0;
  double finest = 0.0, coarsest = 0.0;  ///< the settings fitted (time steps, s)
  int points = 0;
};
std::optional<FittedOrder> FitOrder(const std::vector<SweepRecord>& rows,
                                    const std::vector<size_t>& family_rows,
                                    const std::string& family);

/// One engine at several accuracy levels: its cheapest row reaching each (empty: none does), its
/// rank by wall time among the engines reaching it (1: the cheapest; 0: not reached), and its
/// most accurate row.
struct EngineAtLevels {
  std::string engine;
  std::vector<std::optional<size_t>> cheapest;
  std::vector<int> rank;
  std::optional<size_t> most_accurate;
  std::optional<FittedOrder> order;  ///< over the family of the engine's most accurate run
};
/// Every engine of the rows (not the reference) at each criterion, sorted by rank at
/// `sort_level` (engines that do not reach it after, by their most accurate row's error).
std::vector<EngineAtLevels> RankAtEqualAccuracy(const std::vector<SweepRecord>& rows,
                                                const std::vector<AgreementCriterion>& levels,
                                                size_t sort_level);

}  // namespace rockbench::report
