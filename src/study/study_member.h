#pragma once
/// One run of a study member (the reference or one engine on member i's scene) and its row of
/// members.csv. A row depends only on the study file, the member and the engine (its wall time
/// aside), so it is the same whichever process, worker or MPI rank computed it.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "study/study.h"

namespace rockbench {

/// One row of members.csv.
struct MemberRow {
  int64_t member = 0;
  std::string engine;  ///< "reference" or an engine name
  /// completed | overturned | at_rest | assumption_violated | blow_up (as in summary.json), or
  /// for a run that gave no result: "crash (signal N)" | wall_limit | error.
  std::string status;
  std::string detail;  ///< why, for error, crash and wall_limit rows (one line)
  /// Block geometry of the member, per body (body k at k - 1): p = sqrt(3 g / 4 R) (rad/s) and
  /// alpha = atan(B / H) (rad); empty for a run that gave no result.
  std::vector<double> p_radps, alpha_rad;
  /// Intensity measures of the horizontal base motion over the run (none without one).
  std::optional<double> pga_g, pgv_mps, pgd_m, arias_mps, d5_95_s, pulse_period_s;
  /// Cylinder rows: the peak of the horizontal resultant of [base.horizontal] and
  /// [base.transverse] over the run, max over t of sqrt(a_x^2 + a_y^2), in g0
  /// (MeasureResultantPga); none in planar rows.
  std::optional<double> pga_resultant_g;
  /// Cylinder rows of an overturned run: the azimuth the top fell toward, within (-pi, pi] (rad,
  /// from +x toward +y; summary.json's overturn.azimuth_rad).
  std::optional<double> overturn_azimuth_rad;
  int overturned_block = 0;  ///< 0: none (printed empty), 1..N
  double overturn_t_s = 0.0;
  /// Per body: peak |theta_k|, rad (empty for a run that gave no result).
  std::vector<double> peak_theta_rad;
  int impacts = 0;  ///< impacts at or above the study's min_impact_rate
  double wall_s = 0.0;
  bool has_result = false;  ///< the run gave an outcome (false for crash, wall_limit, error)
  /// Reference rows: the run agrees with its witness (run/reference_witness.h).
  std::optional<bool> converged;
  /// Engine rows: the comparison with the member's reference (compare/agreement.h).
  struct Agreement {
    /// Per body: the largest error of its angle (rad) and its horizon (s).
    std::vector<double> max_abs_error_rad, horizon_s;
    int impacts_matched = 0, reference_impacts = 0;
    /// Both runs overturn the same block or neither does; none when the reference's model
    /// stopped (assumption_violated: it has no outcome to agree with).
    std::optional<bool> overturn_agree;
    std::optional<int> reference_overturned_block;  ///< 0, 1..N (as overturn_agree)
  };
  std::optional<Agreement> agreement;
};

/// Runs `engine` on member `member` in this process (what a worker does). An error of the
/// member's scene or run becomes a row with status "error"; never throws for the member's
/// physics. With `keep_dir`, the run's history.csv and events.csv go to keep_dir/<engine>/.
MemberRow RunMemberHere(const StudyDef& study, int64_t member, const std::string& engine,
                        const std::optional<std::filesystem::path>& keep_dir = std::nullopt);

/// The row of a run that gave no result: its member's geometry and intensities are left empty.
MemberRow FailedRow(int64_t member, const std::string& engine, const std::string& status,
                    const std::string& detail);

/// A row as one line of JSON (a worker's answer) and back; FromJson throws on bad input.
nlohmann::json MemberRowToJson(const MemberRow& row);
MemberRow MemberRowFromJson(const nlohmann::json& j);

/// members.csv's header: member, one column per axis (named by its key), the member's geometry
/// and intensity measures, then the run's columns (docs/ensemble.md lists them). A cylinder
/// study (StudyDef::cylinder) has the cylinder's columns: p1_radps, alpha1_rad, the intensity
/// measures with pga_resultant_g, engine, status, overturned_block, overturn_t_s,
/// overturn_azimuth_rad, peak_tilt1_rad, wall_s, converged, reference_overturned_block,
/// overturn_agree, detail. The per-body
/// columns (p1_radps,alpha1_rad,p2_radps,alpha2_rad, ...; peak_theta1_rad, ...;
/// theta1_max_abs_error_rad, ...; theta1_horizon_s, ...) are those of every body of the study
/// (study.blocks), and of two bodies for a study of one (MembersCsvBodies).
std::string MembersCsvHeader(const StudyDef& study);
/// The bodies members.csv has columns for: the study's, at least two (the file's columns of
/// one-block studies were always those of two).
int MembersCsvBodies(const StudyDef& study);
/// One line of members.csv (with its newline).
std::string MembersCsvLine(const StudyDef& study, const MemberRow& row);

/// The (member, engine) of a members.csv line, read from its first column and its engine
/// column; nullopt for a line that is not a complete row of this study (a line cut short by
/// a killed run).
struct RowKey {
  int64_t member = 0;
  std::string engine;
  auto operator<=>(const RowKey&) const = default;
};
std::optional<RowKey> MembersCsvKey(const StudyDef& study, const std::string& line);

}  // namespace rockbench
