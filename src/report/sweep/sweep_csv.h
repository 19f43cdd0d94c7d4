#pragma once
/// sweep.csv read back: one record per run, with what the work-precision report derives from a
/// single record (its family, its setting's label and value, its largest errors).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace rockbench::report {

/// One body's angle errors against the tight reference: sweep.csv's thetaK_* columns of body K.
struct SweepBodyErrors {
  double max_abs_error_rad = 0.0;  ///< max |angle error| over the run, rad
  double rms_error_rad = 0.0;      ///< rad
  double horizon_s = 0.0;          ///< s
  double peak_rel_error = 0.0;     ///< the peak angle's relative error
  double peak_time_error_s = 0.0;  ///< s
};

/// One row of sweep.csv as read back (columns as src/sweep/sweep.h's SweepCsv writes them).
struct SweepRecord {
  int line = 0;          ///< 1-based line number in sweep.csv
  std::string engine;    ///< an engine's name, or "reference"
  std::string family;    ///< engines: the settings family ("Bullet double (50 iterations)")
  std::string setting;   ///< engines: the point's label ("1e-3", "1/60")
  std::string settings;  ///< engines: the settings besides the step ("k=v;k=v")
  double time_step_s = 0.0;
  std::string integrator;  ///< reference: "dopri5" | "dop853" | "rk4"
  double rtol = 0.0, atol = 0.0;
  double rk4_step_s = 0.0;  ///< s
  std::string status;       ///< the run's status, "error" for a failed run
  double wall_s = 0.0;      ///< s
  /// Per body (body k at k - 1): its angle's errors, from the thetaK_* columns; one body when
  /// the theta2 columns are empty (one block), none for a failed row.
  std::vector<SweepBodyErrors> bodies;
  int impacts_reference = 0, impacts_engine = 0, impacts_matched = 0;
  double max_abs_impact_time_error_s = 0.0;
  bool overturn_agree = false, final_agree = false;
  std::string error;  ///< the run's error message (non-empty: the run failed)
  /// Why the row is not plotted: empty for a usable row; the error message, or the column
  /// holding a non-finite value.
  std::string failure;
  /// Bodies as the columns count them: 2 for one or two bodies (their columns are the same), N
  /// for N >= 3.
  int column_blocks() const { return std::max(2, static_cast<int>(bodies.size())); }
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
/// Max over the bodies of the max |angle error| over the run, rad.
double MaxAngleError(const SweepRecord& r);
/// Max over the bodies of |peak relative error|.
double MaxPeakRelError(const SweepRecord& r);
/// A record's setting in words: "Bullet double (50 iterations), time step 1e-3 s", "reference
/// dopri5, rtol 1e-8", "reference RK4, step 1e-3 s".
std::string SweepSettingDescription(const SweepRecord& r);

}  // namespace rockbench::report
