#pragma once
/// The work-precision report of a sweep folder (`rockbench sweep` output): error against wall
/// time, one curve per engine and setting family, and what it costs to reach a given agreement.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rockbench::report {

/// Writes the report of SWEEP_DIR (it holds sweep.csv) into OUT_DIR/<report name>/: report.html,
/// report.md and figures/ (SVG plus the gnuplot script and data of each). Returns the page
/// folder. Throws std::runtime_error naming the file and line of a malformed sweep.csv.
std::filesystem::path WriteSweepReport(const std::filesystem::path& sweep_dir,
                                       const std::filesystem::path& out_dir);

// The pieces below are public so that they can be tested one by one.

/// The report's folder name under OUT_DIR: the sweep folder's own name ("sweep" when it has
/// none, e.g. "/").
std::string SweepReportName(const std::filesystem::path& sweep_dir);

/// One row of sweep.csv as read back (columns as src/harness/sweep.h's SweepCsv writes them).
struct SweepRecord {
  int line = 0;          ///< 1-based line number in sweep.csv
  std::string engine;    ///< an engine's name, or "reference"
  std::string family;    ///< engines: the settings family ("Bullet double (50 iterations)")
  std::string setting;   ///< engines: the point's label ("1e-3", "1/60")
  std::string settings;  ///< engines: the settings besides the step ("k=v;k=v")
  double time_step_s = 0.0;
  std::string integrator;  ///< reference: "dopri5" | "rk4"
  double rtol = 0.0, atol = 0.0;
  double rk4_step_s = 0.0;  ///< s
  std::string status;       ///< the run's status, "error" for a failed run
  double wall_s = 0.0;      ///< s
  double theta1_max_abs_error_rad = 0.0, theta1_rms_error_rad = 0.0, theta1_horizon_s = 0.0;
  double theta1_peak_rel_error = 0.0, theta1_peak_time_error_s = 0.0;
  bool has_theta2 = false;  ///< two-block scene (the theta2 columns are filled)
  double theta2_max_abs_error_rad = 0.0, theta2_rms_error_rad = 0.0, theta2_horizon_s = 0.0;
  double theta2_peak_rel_error = 0.0, theta2_peak_time_error_s = 0.0;
  int impacts_reference = 0, impacts_engine = 0, impacts_matched = 0;
  double max_abs_impact_time_error_s = 0.0;
  bool overturn_agree = false, final_agree = false;
  std::string error;  ///< the run's error message (non-empty: the run failed)
  /// Why the row is not plotted: empty for a usable row; the error message, or the column
  /// holding a non-finite value.
  std::string failure;
};

/// Parses sweep.csv text; `path` names the file in messages. Throws std::runtime_error
/// "PATH:LINE: ..." for a missing header column, a row with the wrong number of fields, an
/// unknown engine/precision/integrator, a number that does not parse or a setting that is not
/// positive. Non-finite results (nan, inf) are not errors: the row is marked failed.
std::vector<SweepRecord> ParseSweepCsv(const std::string& text, const std::filesystem::path& path);

/// The family of a row: the engine's (sweep.csv "family", e.g. "Bullet double (50
/// iterations)"), "reference dopri5", "reference RK4".
std::string SweepFamily(const SweepRecord& r);
/// The setting that varies within a family, as the sweep labelled it (sweep.csv "setting"): an
/// engine's time step ("1e-3", "1/60"; s), dopri5's rtol ("1e-8"), RK4's step ("2.5e-3"; s).
std::string SweepSettingLabel(const SweepRecord& r);
/// The varying setting's value (time step s, rtol, or step s): smaller is finer.
double SweepSettingValue(const SweepRecord& r);
/// Max over theta1 (and theta2) of the max |angle error| over the run, rad.
double MaxAngleError(const SweepRecord& r);
/// Max over theta1 (and theta2) of |peak relative error|.
double MaxPeakRelError(const SweepRecord& r);
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

/// The criterion: ReachesPeakAgreement(r, tolerance).
AgreementCriterion PeakAgreement(double tolerance, bool two_blocks);
/// A stricter one on the whole history: max |theta_i error| over the run <= fraction x the
/// reference's peak |theta_i| for each block (peak_theta2_rad 0: one block), and the same
/// overturn outcome.
AgreementCriterion HistoryAgreement(double fraction, double peak_theta1_rad,
                                    double peak_theta2_rad);

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
/// With PeakAgreement(peak_tolerance, any row has theta2).
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

}  // namespace rockbench::report
