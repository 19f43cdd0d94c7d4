#pragma once
/// An ensemble folder read back: study.json (the study's axes and engines) and members.csv (one
/// record per member and run, src/study/study_member.h). The report groups, fits and draws
/// from these records only.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rockbench::report {

/// One row of members.csv.
struct EnsembleRecord {
  int line = 0;  ///< 1-based line in members.csv
  long long member = 0;
  std::vector<std::string> axis_values;  ///< in the study's axis order
  std::string engine, status;
  std::optional<double> pga_g, pgv_mps, pulse_period_s, p1_radps, alpha1_rad;
  int overturned_block = 0;  ///< 0: none
  double peak_theta1_rad = 0.0, peak_theta2_rad = 0.0, wall_s = 0.0;
  /// Every block's peak |theta| (block k at k - 1; one entry per block of the study, at least
  /// two: peak_theta1_rad, peak_theta2_rad, then peak_theta3_rad ... of N >= 3 blocks).
  std::vector<double> peak_theta_rad;
  int impacts = 0;
  /// A cylinder study's rows: the peak of the horizontal resultant (g; the fragility's
  /// intensity measure) and an overturn's azimuth (rad). peak_theta1_rad holds the peak tilt.
  std::optional<double> pga_resultant_g, overturn_azimuth_rad;
  double overturn_t_s = 0.0;  ///< when overturned_block != 0, s
  bool has_result = false;    ///< the run gave an outcome (not crash, wall_limit, error)
  /// The run's outcome can be used: it has a result, the model's assumptions held and its state
  /// stayed finite (status non_finite: the run failed).
  bool usable() const {
    return has_result && status != "assumption_violated" && status != "non_finite";
  }
};

struct EnsembleData {
  std::string title;
  std::vector<std::string> axes;     ///< axis keys, in order
  std::vector<std::string> engines;  ///< "reference" first when run
  long long members = 0;
  /// Blocks of the study's stack: 2 for a file of one or two blocks (its columns are the
  /// same), N for one with the peak_theta3_rad ... peak_thetaN_rad columns.
  int blocks = 2;
  int ranks = 1, jobs = 1;
  /// A study of a cylinder rocking in 3-D (members.csv's cylinder columns: peak_tilt1_rad,
  /// pga_resultant_g, overturn_azimuth_rad); blocks is then 1.
  bool cylinder = false;
  double wall_s = 0.0, serial_s = 0.0;
  std::vector<EnsembleRecord> records;  ///< in file order (member, then engine)
  /// The column of `key` among the axes; -1 when the study has no such axis.
  int Axis(const std::string& key) const;
  /// The intensity measure fragility curves and scatter plots use: a cylinder's resultant PGA
  /// (pga_resultant_g), a planar row's pga_g.
  std::optional<double> Pga_g(const EnsembleRecord& r) const {
    return cylinder ? r.pga_resultant_g : r.pga_g;
  }
  /// Its name in figures and tables: "resultant PGA" or "PGA".
  std::string PgaName() const { return cylinder ? "resultant PGA" : "PGA"; }
};

/// True when DIR holds an ensemble (study.json and members.csv).
bool IsEnsembleFolder(const std::filesystem::path& dir);

/// Reads DIR/study.json and DIR/members.csv. Throws ReportInputError naming the file and line
/// of a malformed one.
EnsembleData ReadEnsemble(const std::filesystem::path& dir);

}  // namespace rockbench::report
